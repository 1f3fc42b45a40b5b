// Descriptor sets for kernels (runtime/kernel.h), from what their registry entries reflect: a
// pool sized from the kernels' bindings, sets allocated from their layouts, and writes that take
// each binding's descriptor type from the reflection, so a caller names only the resource. Every
// compute pass kdop builds (the rectify pass, device FLIP's five) binds through it.
#pragma once

#include "core/result.h"
#include "runtime/context.h"
#include "runtime/kernel.h"

#include <cstdint>
#include <span>
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

class KernelSets {
public:
    // A pool for `sets_per_kernel` sets of each of `kernels`. Not copyable; it releases its pool.
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

    // A set of `kernel`'s layout.
    Result<VkDescriptorSet> allocate(const Kernel& kernel);
    // Frees every set allocated, for allocations afresh.
    Result<void> reset();
    // Writes `bound` into `set` of `kernel`'s layout: each binding's type as the kernel reflects
    // it. A binding the kernel lacks, or a resource of the wrong kind for its type, is an error
    // naming the kernel and the binding.
    Result<void> write(const Kernel& kernel, VkDescriptorSet set, std::span<const Bound> bound) const;

private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
};

} // namespace kdop
