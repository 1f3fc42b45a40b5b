// One call from an embedded variant (core/include/kdop/variant.h) to a compute pipeline on the
// caller's VkDevice: descriptor set layouts, pipeline layout and pipeline, all from what the
// registry says about the variant. The shader module is created and destroyed inside the call (a
// pipeline keeps what it needs). C++17, header only; include <vulkan/vulkan.h> and link the Vulkan
// loader as for any Vulkan code.
//
//     kdop::VariantPipeline taa;
//     if (kdop::create_variant_pipeline(device, *variants().find("taa-resolve"), taa) != VK_SUCCESS) ...
//     vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, taa.pipeline);
//     // allocate descriptor sets with taa.set_layouts[0 .. taa.set_layout_count)
//     kdop::destroy_variant_pipeline(device, taa);
#pragma once

#include <kdop/variant.h>

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace kdop {

// Descriptor sets a variant may use: 0 .. kMaxVariantDescriptorSets - 1 (Vulkan guarantees 4).
inline constexpr std::uint32_t kMaxVariantDescriptorSets = 4;

struct VariantPipeline {
    // One layout per set index up to the highest the variant uses (a set it skips gets an empty layout).
    VkDescriptorSetLayout set_layouts[kMaxVariantDescriptorSets] = {};
    std::uint32_t set_layout_count = 0;
    VkPipelineLayout pipeline_layout = VK_NULL_HANDLE; // with the variant's push-constant range, if any
    VkPipeline pipeline = VK_NULL_HANDLE;
};

inline VkDescriptorType to_vulkan(DescriptorType type) {
    return type == DescriptorType::storage_image ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                                 : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
}

// Destroys what `pipeline` holds and empties it; safe on an empty or partly created one.
inline void destroy_variant_pipeline(VkDevice device, VariantPipeline& pipeline,
                                     const VkAllocationCallbacks* allocator = nullptr) {
    if (pipeline.pipeline) vkDestroyPipeline(device, pipeline.pipeline, allocator);
    if (pipeline.pipeline_layout) vkDestroyPipelineLayout(device, pipeline.pipeline_layout, allocator);
    for (std::uint32_t s = 0; s < pipeline.set_layout_count; ++s)
        if (pipeline.set_layouts[s]) vkDestroyDescriptorSetLayout(device, pipeline.set_layouts[s], allocator);
    pipeline = VariantPipeline{};
}

// Creates `out` for `variant` on `device`. On failure returns the Vulkan error
// (VK_ERROR_INITIALIZATION_FAILED when the variant uses a set beyond kMaxVariantDescriptorSets) and
// leaves `out` empty, with nothing left to destroy.
inline VkResult create_variant_pipeline(VkDevice device, const Variant& variant, VariantPipeline& out,
                                        VkPipelineCache cache = VK_NULL_HANDLE,
                                        const VkAllocationCallbacks* allocator = nullptr) {
    out = VariantPipeline{};
    for (std::uint32_t i = 0; i < variant.binding_count; ++i) {
        if (variant.bindings[i].set >= kMaxVariantDescriptorSets) return VK_ERROR_INITIALIZATION_FAILED;
        if (variant.bindings[i].set + 1 > out.set_layout_count) out.set_layout_count = variant.bindings[i].set + 1;
    }
    VkResult result = VK_SUCCESS;
    for (std::uint32_t s = 0; s < out.set_layout_count && result == VK_SUCCESS; ++s) {
        std::vector<VkDescriptorSetLayoutBinding> bindings;
        for (std::uint32_t i = 0; i < variant.binding_count; ++i)
            if (variant.bindings[i].set == s)
                bindings.push_back({variant.bindings[i].binding, to_vulkan(variant.bindings[i].type), 1,
                                    VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
        VkDescriptorSetLayoutCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
        info.bindingCount = static_cast<std::uint32_t>(bindings.size());
        info.pBindings = bindings.data();
        result = vkCreateDescriptorSetLayout(device, &info, allocator, &out.set_layouts[s]);
    }

    if (result == VK_SUCCESS) {
        VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, variant.push_constant_size};
        VkPipelineLayoutCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
        info.setLayoutCount = out.set_layout_count;
        info.pSetLayouts = out.set_layouts;
        info.pushConstantRangeCount = variant.push_constant_size ? 1 : 0;
        info.pPushConstantRanges = &push;
        result = vkCreatePipelineLayout(device, &info, allocator, &out.pipeline_layout);
    }

    VkShaderModule module = VK_NULL_HANDLE;
    if (result == VK_SUCCESS) {
        VkShaderModuleCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
        info.codeSize = variant.spirv_word_count * sizeof(std::uint32_t);
        info.pCode = variant.spirv;
        result = vkCreateShaderModule(device, &info, allocator, &module);
    }
    if (result == VK_SUCCESS) {
        VkComputePipelineCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
        info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
        info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        info.stage.module = module;
        info.stage.pName = variant.entry_point;
        info.layout = out.pipeline_layout;
        result = vkCreateComputePipelines(device, cache, 1, &info, allocator, &out.pipeline);
        vkDestroyShaderModule(device, module, allocator);
    }
    if (result != VK_SUCCESS) destroy_variant_pipeline(device, out, allocator);
    return result;
}

} // namespace kdop
