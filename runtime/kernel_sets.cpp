#include "runtime/kernel_sets.h"

#include "runtime/vulkan_error.h"

#include <kdop/vulkan_pipeline.h>

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace kdop {
namespace {

// What kind of resource a descriptor type takes.
enum class Kind { image, buffer, texels };
Kind kind_of(DescriptorType type) {
    switch (type) {
    case DescriptorType::uniform_texel_buffer:
    case DescriptorType::storage_texel_buffer: return Kind::texels;
    case DescriptorType::uniform_buffer:
    case DescriptorType::storage_buffer: return Kind::buffer;
    default: return Kind::image;
    }
}

} // namespace

Result<KernelSets> KernelSets::create(const Context& context, std::span<const ReflectedSet> programs,
                                      std::uint32_t sets_per_program) {
    std::map<VkDescriptorType, std::uint32_t> counts;
    for (const ReflectedSet& program : programs)
        for (const Kernel::Binding& b : program.bindings) counts[to_vulkan(b.type)] += sets_per_program;
    std::vector<VkDescriptorPoolSize> sizes;
    for (const auto& [type, count] : counts) sizes.push_back({type, count});
    return create(context, sizes, std::max<std::uint32_t>(1, std::uint32_t(programs.size()) * sets_per_program));
}

Result<KernelSets> KernelSets::create(const Context& context, std::span<const Kernel* const> kernels,
                                      std::uint32_t sets_per_kernel) {
    std::vector<ReflectedSet> programs;
    for (const Kernel* kernel : kernels) programs.push_back(reflected_set(*kernel));
    return create(context, std::span<const ReflectedSet>(programs), sets_per_kernel);
}

Result<KernelSets> KernelSets::create(const Context& context, std::span<const VkDescriptorPoolSize> sizes,
                                      std::uint32_t sets) {
    VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool.maxSets = sets;
    pool.poolSizeCount = std::uint32_t(sizes.size());
    pool.pPoolSizes = sizes.data();
    KernelSets made;
    made.device_ = context.device();
    if (!sizes.empty()) KDOP_VK_TRY(vkCreateDescriptorPool(context.device(), &pool, nullptr, &made.pool_));
    return made;
}

KernelSets& KernelSets::operator=(KernelSets&& other) noexcept {
    std::swap(device_, other.device_);
    std::swap(pool_, other.pool_);
    return *this;
}

KernelSets::~KernelSets() {
    if (pool_) vkDestroyDescriptorPool(device_, pool_, nullptr);
}

Result<VkDescriptorSet> KernelSets::allocate(const ReflectedSet& program) {
    VkDescriptorSetLayout layout = program.layout;
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool_;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &layout;
    VkDescriptorSet set = VK_NULL_HANDLE;
    KDOP_VK_TRY(vkAllocateDescriptorSets(device_, &alloc, &set));
    return set;
}

Result<void> KernelSets::reset() {
    KDOP_VK_TRY(vkResetDescriptorPool(device_, pool_, 0));
    return {};
}

Result<void> KernelSets::write(const ReflectedSet& program, VkDescriptorSet set, std::span<const Bound> bound) const {
    // Filled before any write points into them: the writes hold their addresses.
    std::vector<VkDescriptorImageInfo> images(bound.size());
    std::vector<VkDescriptorBufferInfo> buffers(bound.size());
    std::vector<VkBufferView> texels(bound.size());
    std::vector<VkWriteDescriptorSet> writes;
    for (std::size_t i = 0; i < bound.size(); ++i) {
        const auto reflected = std::find_if(program.bindings.begin(), program.bindings.end(),
                                            [&](const Kernel::Binding& b) { return b.binding == bound[i].binding; });
        if (reflected == program.bindings.end())
            return fail(fmt::format("internal error: {} has no binding {}", program.name, bound[i].binding));
        const Kind kind = kind_of(reflected->type);
        const bool matches = std::visit(
            [&](const auto& r) {
                using R = std::decay_t<decltype(r)>;
                return std::is_same_v<R, BoundImage>    ? kind == Kind::image
                       : std::is_same_v<R, BoundBuffer> ? kind == Kind::buffer
                                                        : kind == Kind::texels;
            },
            bound[i].resource);
        if (!matches)
            return fail(fmt::format("internal error: {} binding {} ('{}') is a {}, not what it was given", program.name,
                                    reflected->binding, reflected->name, to_string(reflected->type)));
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = set;
        w.dstBinding = reflected->binding;
        w.descriptorCount = 1;
        w.descriptorType = to_vulkan(reflected->type);
        if (const auto* image = std::get_if<BoundImage>(&bound[i].resource)) {
            images[i] = {image->sampler, image->view, image->layout};
            w.pImageInfo = &images[i];
        } else if (const auto* buffer = std::get_if<BoundBuffer>(&bound[i].resource)) {
            buffers[i] = {buffer->buffer, 0, VK_WHOLE_SIZE};
            w.pBufferInfo = &buffers[i];
        } else {
            texels[i] = std::get<BoundTexels>(bound[i].resource).view;
            w.pTexelBufferView = &texels[i];
        }
        writes.push_back(w);
    }
    vkUpdateDescriptorSets(device_, std::uint32_t(writes.size()), writes.data(), 0, nullptr);
    return {};
}

} // namespace kdop
