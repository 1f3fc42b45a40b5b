// Descriptor sets for reflected programs, from what their registry entries reflect: a pool sized
// from the programs' bindings, sets allocated from their layouts, and writes that take each
// binding's descriptor type from the reflection, so a caller names only the resource. A program is
// a kernel (runtime/kernel.h) or the raster pass's vertex and fragment stages (runtime/raster_pass.h):
// every pass kdop builds (the rectify pass, device FLIP's five, the raster pass) binds through it.
#pragma once

#include "core/result.h"
#include "runtime/context.h"
#include "runtime/kernel.h"

#include <cstdint>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

namespace kdop {

// What one binding is given: an image (with the sampler a combined image sampler takes), a buffer
// (whole), or a texel buffer's view.
struct BoundImage {
    VkImageView view = VK_NULL_HANDLE;
    VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
    VkSampler sampler = VK_NULL_HANDLE;
};
struct BoundBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
};
struct BoundTexels {
    VkBufferView view = VK_NULL_HANDLE;
};
using BoundResource = std::variant<BoundImage, BoundBuffer, BoundTexels>;
struct Bound {
    std::uint32_t binding = 0;
    BoundResource resource;
};

// A program's descriptor set 0 as its registry entries reflect it: the layout made from them and
// the bindings it holds. A view; what it names must outlive its use.
struct ReflectedSet {
    std::string_view name; // the program's, for messages
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    std::span<const Kernel::Binding> bindings;
};
// A kernel's.
inline ReflectedSet reflected_set(const Kernel& kernel) {
    return {kernel.name(), kernel.set_layout(), kernel.bindings()};
}

class KernelSets {
public:
    // A pool for `sets_per_program` sets of each of `programs`. Not copyable; it releases its pool.
    static Result<KernelSets> create(const Context& context, std::span<const ReflectedSet> programs,
                                     std::uint32_t sets_per_program = 1);
    // The same for kernels.
    static Result<KernelSets> create(const Context& context, std::span<const Kernel* const> kernels,
                                     std::uint32_t sets_per_kernel = 1);
    // A pool of `sizes` for at most `sets` sets, for kernels a pass does not know yet.
    static Result<KernelSets> create(const Context& context, std::span<const VkDescriptorPoolSize> sizes,
                                     std::uint32_t sets);
    KernelSets() = default;
    KernelSets(KernelSets&& other) noexcept { *this = std::move(other); }
    KernelSets& operator=(KernelSets&& other) noexcept;
    KernelSets(const KernelSets&) = delete;
    KernelSets& operator=(const KernelSets&) = delete;
    ~KernelSets();

    // A set of `program`'s layout.
    Result<VkDescriptorSet> allocate(const ReflectedSet& program);
    Result<VkDescriptorSet> allocate(const Kernel& kernel) { return allocate(reflected_set(kernel)); }
    // Frees every set allocated, for allocations afresh.
    Result<void> reset();
    // Writes `bound` into `set` of `program`'s layout: each binding's type as the program reflects
    // it. A binding the program lacks, or a resource of the wrong kind for its type, is an error
    // naming the program and the binding.
    Result<void> write(const ReflectedSet& program, VkDescriptorSet set, std::span<const Bound> bound) const;
    Result<void> write(const Kernel& kernel, VkDescriptorSet set, std::span<const Bound> bound) const {
        return write(reflected_set(kernel), set, bound);
    }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
};

} // namespace kdop
