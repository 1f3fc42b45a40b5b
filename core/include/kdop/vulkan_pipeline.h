// From embedded registry entries (core/include/kdop/variant.h) to pipelines on the caller's
// VkDevice: descriptor set layouts, pipeline layout and pipeline, all from what the registry says
// about the entries; then a descriptor pool sized for them and set writes whose type and count come
// from the reflection. Compute pipelines from one entry, graphics pipelines from a vertex and a
// fragment entry (into a render pass or, with dynamic rendering, into the caller's formats). Shader
// modules are created and destroyed inside the calls (a pipeline keeps what it needs).
//
// C++17, header only. Every Vulkan call goes through a VariantVulkanFunctions table, which
// load_variant_functions() fills from vkGetDeviceProcAddr, so the helper works with volk and with
// VK_NO_PROTOTYPES; without VK_NO_PROTOTYPES the overloads without a table use the loader's
// prototypes (link the Vulkan loader then, as for any Vulkan code).
//
//     kdop::VariantVulkanFunctions vk;
//     kdop::load_variant_functions(device, vkGetDeviceProcAddr, vk);
//     kdop::VariantPipeline taa;
//     if (kdop::create_variant_pipeline(vk, device, *variants().find("taa_resolve"), taa) != VK_SUCCESS)
//         log(taa.failure);
//     vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, taa.pipeline);
//     kdop::create_variant_descriptor_pool(vk, device, taa, frames_in_flight, pool);
//     kdop::allocate_variant_descriptor_sets(vk, device, pool, taa, sets);
//     VkWriteDescriptorSet w = kdop::variant_descriptor_write(*kdop::find_binding(entry, "history_frame"), sets[0]);
//     w.pImageInfo = &history;
//     kdop::destroy_variant_pipeline(vk, device, taa);
#pragma once

#include <kdop/variant.h>

#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

namespace kdop {

// Descriptor sets an entry may use: 0 .. kMaxVariantDescriptorSets - 1 (Vulkan guarantees 4).
inline constexpr std::uint32_t kMaxVariantDescriptorSets = 4;

// The device-level entry points the helper calls.
struct VariantVulkanFunctions {
    PFN_vkCreateDescriptorSetLayout create_descriptor_set_layout = nullptr;
    PFN_vkDestroyDescriptorSetLayout destroy_descriptor_set_layout = nullptr;
    PFN_vkCreatePipelineLayout create_pipeline_layout = nullptr;
    PFN_vkDestroyPipelineLayout destroy_pipeline_layout = nullptr;
    PFN_vkCreateShaderModule create_shader_module = nullptr;
    PFN_vkDestroyShaderModule destroy_shader_module = nullptr;
    PFN_vkCreateComputePipelines create_compute_pipelines = nullptr;
    PFN_vkCreateGraphicsPipelines create_graphics_pipelines = nullptr;
    PFN_vkDestroyPipeline destroy_pipeline = nullptr;
    PFN_vkCreateDescriptorPool create_descriptor_pool = nullptr;
    PFN_vkDestroyDescriptorPool destroy_descriptor_pool = nullptr;
    PFN_vkAllocateDescriptorSets allocate_descriptor_sets = nullptr;
};

// Fills `out` through `get_device_proc_addr` (the loader's, or volk's vkGetDeviceProcAddr).
// VK_ERROR_INITIALIZATION_FAILED when the device lacks one of them.
inline VkResult load_variant_functions(VkDevice device, PFN_vkGetDeviceProcAddr get_device_proc_addr,
                                       VariantVulkanFunctions& out) {
    out = VariantVulkanFunctions{};
    bool complete = get_device_proc_addr != nullptr;
    auto load = [&](auto& function, const char* name) {
        if (!complete) return;
        function = reinterpret_cast<std::remove_reference_t<decltype(function)>>(get_device_proc_addr(device, name));
        complete = function != nullptr;
    };
    load(out.create_descriptor_set_layout, "vkCreateDescriptorSetLayout");
    load(out.destroy_descriptor_set_layout, "vkDestroyDescriptorSetLayout");
    load(out.create_pipeline_layout, "vkCreatePipelineLayout");
    load(out.destroy_pipeline_layout, "vkDestroyPipelineLayout");
    load(out.create_shader_module, "vkCreateShaderModule");
    load(out.destroy_shader_module, "vkDestroyShaderModule");
    load(out.create_compute_pipelines, "vkCreateComputePipelines");
    load(out.create_graphics_pipelines, "vkCreateGraphicsPipelines");
    load(out.destroy_pipeline, "vkDestroyPipeline");
    load(out.create_descriptor_pool, "vkCreateDescriptorPool");
    load(out.destroy_descriptor_pool, "vkDestroyDescriptorPool");
    load(out.allocate_descriptor_sets, "vkAllocateDescriptorSets");
    return complete ? VK_SUCCESS : VK_ERROR_INITIALIZATION_FAILED;
}

#ifndef VK_NO_PROTOTYPES
// The table of the loader's own prototypes.
inline VariantVulkanFunctions prototype_variant_functions() {
    return {vkCreateDescriptorSetLayout, vkDestroyDescriptorSetLayout, vkCreatePipelineLayout,
            vkDestroyPipelineLayout,     vkCreateShaderModule,         vkDestroyShaderModule,
            vkCreateComputePipelines,    vkCreateGraphicsPipelines,    vkDestroyPipeline,
            vkCreateDescriptorPool,      vkDestroyDescriptorPool,      vkAllocateDescriptorSets};
}
#endif

struct VariantPipeline {
    // One layout per set index up to the highest the entries use (a set they skip gets an empty layout).
    VkDescriptorSetLayout set_layouts[kMaxVariantDescriptorSets] = {};
    std::uint32_t set_layout_count = 0;
    VkPipelineLayout pipeline_layout = VK_NULL_HANDLE; // with the entries' push-constant range, if any
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkShaderStageFlags push_constant_stages = 0; // what vkCmdPushConstants takes; 0 without push constants
    std::uint32_t push_constant_size = 0;
    std::vector<VkDescriptorPoolSize> pool_sizes; // one of each set: what create_variant_descriptor_pool sizes
    const char* failure = nullptr;                // after a failed creation: what failed, in words
};

inline VkDescriptorType to_vulkan(DescriptorType type) {
    switch (type) {
    case DescriptorType::combined_image_sampler: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    case DescriptorType::storage_image: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    case DescriptorType::sampled_image: return VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    case DescriptorType::sampler: return VK_DESCRIPTOR_TYPE_SAMPLER;
    case DescriptorType::uniform_texel_buffer: return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    case DescriptorType::storage_texel_buffer: return VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
    case DescriptorType::uniform_buffer: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case DescriptorType::storage_buffer: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    }
    return VK_DESCRIPTOR_TYPE_MAX_ENUM;
}

inline VkShaderStageFlagBits to_vulkan(ShaderStage stage) {
    return static_cast<VkShaderStageFlagBits>(vulkan_stage_bit(stage));
}

// The binding called `name` in `entry`, or nullptr.
inline const DescriptorBinding* find_binding(const Variant& entry, const char* name) {
    for (std::uint32_t i = 0; i < entry.binding_count; ++i)
        if (std::strcmp(entry.bindings[i].name, name) == 0) return &entry.bindings[i];
    return nullptr;
}

// A write of every descriptor of `binding` into `set`, type and count as reflected; point its
// pImageInfo, pBufferInfo or pTexelBufferView at binding.count elements.
inline VkWriteDescriptorSet variant_descriptor_write(const DescriptorBinding& binding, VkDescriptorSet set) {
    VkWriteDescriptorSet write{};
    write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    write.dstSet = set;
    write.dstBinding = binding.binding;
    write.descriptorCount = binding.count;
    write.descriptorType = to_vulkan(binding.type);
    return write;
}

// Destroys what `pipeline` holds and empties it; safe on an empty or partly created one.
inline void destroy_variant_pipeline(const VariantVulkanFunctions& vk, VkDevice device, VariantPipeline& pipeline,
                                     const VkAllocationCallbacks* allocator = nullptr) {
    if (pipeline.pipeline) vk.destroy_pipeline(device, pipeline.pipeline, allocator);
    if (pipeline.pipeline_layout) vk.destroy_pipeline_layout(device, pipeline.pipeline_layout, allocator);
    for (std::uint32_t s = 0; s < pipeline.set_layout_count; ++s)
        if (pipeline.set_layouts[s]) vk.destroy_descriptor_set_layout(device, pipeline.set_layouts[s], allocator);
    const char* failure = pipeline.failure;
    pipeline = VariantPipeline{};
    pipeline.failure = failure;
}

namespace detail {

// Set layouts, pool sizes, push-constant range and pipeline layout for `entries` together: a binding
// two entries share must agree on type and count, and is visible to both stages.
inline VkResult create_layouts(const VariantVulkanFunctions& vk, VkDevice device, const Variant* const* entries,
                               std::uint32_t entry_count, VariantPipeline& out,
                               const VkAllocationCallbacks* allocator) {
    std::vector<VkDescriptorSetLayoutBinding> merged[kMaxVariantDescriptorSets];
    for (std::uint32_t e = 0; e < entry_count; ++e) {
        const Variant& entry = *entries[e];
        for (std::uint32_t i = 0; i < entry.binding_count; ++i) {
            const DescriptorBinding& b = entry.bindings[i];
            if (b.set >= kMaxVariantDescriptorSets) {
                out.failure = "an entry uses a descriptor set beyond kMaxVariantDescriptorSets";
                return VK_ERROR_INITIALIZATION_FAILED;
            }
            if (b.set + 1 > out.set_layout_count) out.set_layout_count = b.set + 1;
            VkDescriptorSetLayoutBinding* found = nullptr;
            for (VkDescriptorSetLayoutBinding& m : merged[b.set])
                if (m.binding == b.binding) found = &m;
            if (!found) {
                merged[b.set].push_back({b.binding, to_vulkan(b.type), b.count, b.stages, nullptr});
            } else if (found->descriptorType != to_vulkan(b.type) || found->descriptorCount != b.count) {
                out.failure = "two entries declare the same set and binding with different types or counts";
                return VK_ERROR_INITIALIZATION_FAILED;
            } else {
                found->stageFlags |= b.stages;
            }
        }
        if (entry.push_constant_size) {
            out.push_constant_stages |= vulkan_stage_bit(entry.stage);
            if (entry.push_constant_size > out.push_constant_size) out.push_constant_size = entry.push_constant_size;
        }
    }

    VkResult result = VK_SUCCESS;
    for (std::uint32_t s = 0; s < out.set_layout_count && result == VK_SUCCESS; ++s) {
        for (const VkDescriptorSetLayoutBinding& b : merged[s]) {
            VkDescriptorPoolSize* size = nullptr;
            for (VkDescriptorPoolSize& p : out.pool_sizes)
                if (p.type == b.descriptorType) size = &p;
            if (size)
                size->descriptorCount += b.descriptorCount;
            else
                out.pool_sizes.push_back({b.descriptorType, b.descriptorCount});
        }
        VkDescriptorSetLayoutCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
        info.bindingCount = static_cast<std::uint32_t>(merged[s].size());
        info.pBindings = merged[s].data();
        result = vk.create_descriptor_set_layout(device, &info, allocator, &out.set_layouts[s]);
        if (result != VK_SUCCESS) out.failure = "vkCreateDescriptorSetLayout failed";
    }
    if (result != VK_SUCCESS) return result;

    // One range over both stages: a stage may be given more of the block than it reads.
    VkPushConstantRange push{out.push_constant_stages, 0, out.push_constant_size};
    VkPipelineLayoutCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    info.setLayoutCount = out.set_layout_count;
    info.pSetLayouts = out.set_layouts;
    info.pushConstantRangeCount = out.push_constant_size ? 1 : 0;
    info.pPushConstantRanges = &push;
    result = vk.create_pipeline_layout(device, &info, allocator, &out.pipeline_layout);
    if (result != VK_SUCCESS) out.failure = "vkCreatePipelineLayout failed";
    return result;
}

inline VkResult create_module(const VariantVulkanFunctions& vk, VkDevice device, const Variant& entry,
                              VkShaderModule& module, VariantPipeline& out, const VkAllocationCallbacks* allocator) {
    VkShaderModuleCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    info.codeSize = entry.spirv_word_count * sizeof(std::uint32_t);
    info.pCode = entry.spirv;
    VkResult result = vk.create_shader_module(device, &info, allocator, &module);
    if (result != VK_SUCCESS) out.failure = "vkCreateShaderModule failed";
    return result;
}

inline VkPipelineShaderStageCreateInfo stage_info(const Variant& entry, VkShaderModule module) {
    VkPipelineShaderStageCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage = to_vulkan(entry.stage);
    info.module = module;
    info.pName = entry.entry_point;
    return info;
}

} // namespace detail

// Creates `out` for the compute entry `entry` on `device`. On failure returns the Vulkan error
// (VK_ERROR_INITIALIZATION_FAILED for an entry that is not a compute shader, or that uses a set
// beyond kMaxVariantDescriptorSets), says why in out.failure, and leaves nothing to destroy.
inline VkResult create_variant_pipeline(const VariantVulkanFunctions& vk, VkDevice device, const Variant& entry,
                                        VariantPipeline& out, VkPipelineCache cache = VK_NULL_HANDLE,
                                        const VkAllocationCallbacks* allocator = nullptr) {
    out = VariantPipeline{};
    if (entry.stage != ShaderStage::compute) {
        out.failure = "a compute pipeline needs a compute entry";
        return VK_ERROR_INITIALIZATION_FAILED;
    }
    const Variant* entries[] = {&entry};
    VkResult result = detail::create_layouts(vk, device, entries, 1, out, allocator);
    VkShaderModule module = VK_NULL_HANDLE;
    if (result == VK_SUCCESS) result = detail::create_module(vk, device, entry, module, out, allocator);
    if (result == VK_SUCCESS) {
        VkComputePipelineCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
        info.stage = detail::stage_info(entry, module);
        info.layout = out.pipeline_layout;
        result = vk.create_compute_pipelines(device, cache, 1, &info, allocator, &out.pipeline);
        if (result != VK_SUCCESS) out.failure = "vkCreateComputePipelines failed";
        vk.destroy_shader_module(device, module, allocator);
    }
    if (result != VK_SUCCESS) destroy_variant_pipeline(vk, device, out, allocator);
    return result;
}

// Where a graphics pipeline draws: a render pass and subpass of the caller's, or, when render_pass
// is null, dynamic rendering (Vulkan 1.3 or VK_KHR_dynamic_rendering, enabled by the caller) into
// these formats. Either way the pipeline blends (writes) one color attachment per fragment output
// (Variant::color_output_count), so the subpass or the rendering must have that many.
struct GraphicsTargets {
    VkRenderPass render_pass = VK_NULL_HANDLE;
    std::uint32_t subpass = 0;
    const VkFormat* color_formats = nullptr; // dynamic rendering: one per fragment color output
    std::uint32_t color_format_count = 0;
    VkFormat depth_format = VK_FORMAT_UNDEFINED;
};

// The fixed-function state, by default a full-screen pass's: no vertex input (the vertex shader
// makes its triangle from gl_VertexIndex), a triangle list, no culling, no depth test, no blending,
// one sample; viewport and scissor are dynamic (vkCmdSetViewport, vkCmdSetScissor).
struct GraphicsState {
    const VkPipelineVertexInputStateCreateInfo* vertex_input = nullptr; // null: no vertex input
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkCullModeFlags cull_mode = VK_CULL_MODE_NONE;
    bool depth_test = false;
    bool depth_write = false;
    VkCompareOp depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
};

// Creates `out`, a graphics pipeline of the vertex entry `vertex` and fragment entry `fragment`
// (bindings and push constants of both in one layout), drawing into `targets`. Errors as for
// create_variant_pipeline, and VK_ERROR_INITIALIZATION_FAILED when the stages are not a vertex and
// a fragment entry or dynamic rendering is given fewer formats than the fragment entry's outputs.
inline VkResult create_variant_graphics_pipeline(const VariantVulkanFunctions& vk, VkDevice device,
                                                 const Variant& vertex, const Variant& fragment,
                                                 const GraphicsTargets& targets, VariantPipeline& out,
                                                 const GraphicsState& state = {},
                                                 VkPipelineCache cache = VK_NULL_HANDLE,
                                                 const VkAllocationCallbacks* allocator = nullptr) {
    out = VariantPipeline{};
    if (vertex.stage != ShaderStage::vertex || fragment.stage != ShaderStage::fragment) {
        out.failure = "a graphics pipeline needs a vertex entry and a fragment entry";
        return VK_ERROR_INITIALIZATION_FAILED;
    }
    if (!targets.render_pass && targets.color_format_count < fragment.color_output_count) {
        out.failure = "dynamic rendering needs a color format for each of the fragment entry's outputs";
        return VK_ERROR_INITIALIZATION_FAILED;
    }
    const Variant* entries[] = {&vertex, &fragment};
    VkResult result = detail::create_layouts(vk, device, entries, 2, out, allocator);
    VkShaderModule modules[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
    for (int i = 0; i < 2 && result == VK_SUCCESS; ++i)
        result = detail::create_module(vk, device, *entries[i], modules[i], out, allocator);
    if (result == VK_SUCCESS) {
        const VkPipelineShaderStageCreateInfo stages[] = {detail::stage_info(vertex, modules[0]),
                                                          detail::stage_info(fragment, modules[1])};
        VkPipelineVertexInputStateCreateInfo no_vertex_input{};
        no_vertex_input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
        VkPipelineInputAssemblyStateCreateInfo assembly{};
        assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
        assembly.topology = state.topology;
        VkPipelineViewportStateCreateInfo viewport{};
        viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
        viewport.viewportCount = 1;
        viewport.scissorCount = 1;
        VkPipelineRasterizationStateCreateInfo raster{};
        raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
        raster.polygonMode = VK_POLYGON_MODE_FILL;
        raster.cullMode = state.cull_mode;
        raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        raster.lineWidth = 1.0f;
        VkPipelineMultisampleStateCreateInfo multisample{};
        multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
        multisample.rasterizationSamples = state.samples;
        VkPipelineDepthStencilStateCreateInfo depth{};
        depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
        depth.depthTestEnable = state.depth_test ? VK_TRUE : VK_FALSE;
        depth.depthWriteEnable = state.depth_write ? VK_TRUE : VK_FALSE;
        depth.depthCompareOp = state.depth_compare;
        std::vector<VkPipelineColorBlendAttachmentState> attachments(fragment.color_output_count);
        for (VkPipelineColorBlendAttachmentState& a : attachments)
            a.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                               VK_COLOR_COMPONENT_A_BIT;
        VkPipelineColorBlendStateCreateInfo blend{};
        blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
        blend.attachmentCount = static_cast<std::uint32_t>(attachments.size());
        blend.pAttachments = attachments.data();
        const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
        VkPipelineDynamicStateCreateInfo dynamic{};
        dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
        dynamic.dynamicStateCount = 2;
        dynamic.pDynamicStates = dynamic_states;
        // VkPipelineRenderingCreateInfo is Vulkan 1.3's name for VkPipelineRenderingCreateInfoKHR.
        VkPipelineRenderingCreateInfoKHR rendering{};
        rendering.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO_KHR;
        rendering.colorAttachmentCount = targets.color_format_count;
        rendering.pColorAttachmentFormats = targets.color_formats;
        rendering.depthAttachmentFormat = targets.depth_format;

        VkGraphicsPipelineCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
        info.pNext = targets.render_pass ? nullptr : &rendering;
        info.stageCount = 2;
        info.pStages = stages;
        info.pVertexInputState = state.vertex_input ? state.vertex_input : &no_vertex_input;
        info.pInputAssemblyState = &assembly;
        info.pViewportState = &viewport;
        info.pRasterizationState = &raster;
        info.pMultisampleState = &multisample;
        info.pDepthStencilState = &depth;
        info.pColorBlendState = &blend;
        info.pDynamicState = &dynamic;
        info.layout = out.pipeline_layout;
        info.renderPass = targets.render_pass;
        info.subpass = targets.subpass;
        result = vk.create_graphics_pipelines(device, cache, 1, &info, allocator, &out.pipeline);
        if (result != VK_SUCCESS) out.failure = "vkCreateGraphicsPipelines failed";
    }
    for (VkShaderModule module : modules)
        if (module) vk.destroy_shader_module(device, module, allocator);
    if (result != VK_SUCCESS) destroy_variant_pipeline(vk, device, out, allocator);
    return result;
}

// A pool that holds `copies` (at least 1) of each of the pipeline's descriptor sets, e.g. one copy
// per frame in flight. A pipeline without descriptor sets needs none: `out` is then VK_NULL_HANDLE.
inline VkResult create_variant_descriptor_pool(const VariantVulkanFunctions& vk, VkDevice device,
                                               const VariantPipeline& pipeline, std::uint32_t copies,
                                               VkDescriptorPool& out,
                                               const VkAllocationCallbacks* allocator = nullptr) {
    out = VK_NULL_HANDLE;
    if (pipeline.set_layout_count == 0) return VK_SUCCESS;
    if (copies == 0) return VK_ERROR_INITIALIZATION_FAILED;
    std::vector<VkDescriptorPoolSize> sizes = pipeline.pool_sizes;
    for (VkDescriptorPoolSize& s : sizes) s.descriptorCount *= copies;
    VkDescriptorPoolCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    info.maxSets = pipeline.set_layout_count * copies;
    info.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
    info.pPoolSizes = sizes.data();
    return vk.create_descriptor_pool(device, &info, allocator, &out);
}

// Allocates one set per layout of `pipeline` into sets[0 .. pipeline.set_layout_count).
inline VkResult allocate_variant_descriptor_sets(const VariantVulkanFunctions& vk, VkDevice device,
                                                 VkDescriptorPool pool, const VariantPipeline& pipeline,
                                                 VkDescriptorSet* sets) {
    VkDescriptorSetAllocateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    info.descriptorPool = pool;
    info.descriptorSetCount = pipeline.set_layout_count;
    info.pSetLayouts = pipeline.set_layouts;
    return vk.allocate_descriptor_sets(device, &info, sets);
}

#ifndef VK_NO_PROTOTYPES
// The same through the loader's prototypes.
inline void destroy_variant_pipeline(VkDevice device, VariantPipeline& pipeline,
                                     const VkAllocationCallbacks* allocator = nullptr) {
    destroy_variant_pipeline(prototype_variant_functions(), device, pipeline, allocator);
}
inline VkResult create_variant_pipeline(VkDevice device, const Variant& entry, VariantPipeline& out,
                                        VkPipelineCache cache = VK_NULL_HANDLE,
                                        const VkAllocationCallbacks* allocator = nullptr) {
    return create_variant_pipeline(prototype_variant_functions(), device, entry, out, cache, allocator);
}
#endif

} // namespace kdop
