#include "kernel.h"

#include "vulkan_error.h"

#include <fmt/format.h>

#include <chrono>
#include <vector>

namespace kdop {

Result<std::unique_ptr<Kernel>> Kernel::create(const Context& context, const Variant& variant) {
    std::unique_ptr<Kernel> k(new Kernel(context));
    VkDevice device = context.device();
    k->name_ = variant.name;
    for (uint32_t i = 0; i < variant.binding_count; ++i)
        k->bindings_.push_back({variant.bindings[i].binding, variant.bindings[i].type, variant.bindings[i].name});
    for (uint32_t i = 0; i < variant.push_constant_count; ++i)
        k->push_constants_.push_back(
            {variant.push_constants[i].name, variant.push_constants[i].offset, variant.push_constants[i].size});
    k->push_constant_size_ = variant.push_constant_size;
    k->local_size_ = {variant.local_size[0], variant.local_size[1], variant.local_size[2]};

    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (uint32_t i = 0; i < variant.binding_count; ++i) {
        const DescriptorBinding& b = variant.bindings[i];
        if (b.set != 0)
            return fail(fmt::format("{}: binding '{}' is in descriptor set {}; the runtime binds set 0 only",
                                    variant.name, b.name, b.set));
        bindings.push_back({b.binding,
                            b.type == DescriptorType::storage_image ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                                                    : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                            1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    }
    VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.bindingCount = static_cast<uint32_t>(bindings.size());
    set_info.pBindings = bindings.data();
    KDOP_VK_TRY(vkCreateDescriptorSetLayout(device, &set_info, nullptr, &k->set_layout_));

    VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, variant.push_constant_size};
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &k->set_layout_;
    layout_info.pushConstantRangeCount = variant.push_constant_size ? 1 : 0;
    layout_info.pPushConstantRanges = &push;
    KDOP_VK_TRY(vkCreatePipelineLayout(device, &layout_info, nullptr, &k->layout_));

    auto start = std::chrono::steady_clock::now();
    VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module_info.codeSize = variant.spirv_word_count * sizeof(uint32_t);
    module_info.pCode = variant.spirv;
    VkShaderModule module = VK_NULL_HANDLE;
    KDOP_VK_TRY(vkCreateShaderModule(device, &module_info, nullptr, &module));

    VkComputePipelineCreateInfo pipeline_info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    pipeline_info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_info.stage.module = module;
    pipeline_info.stage.pName = variant.entry_point;
    pipeline_info.layout = k->layout_;
    VkResult created = vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &k->pipeline_);
    vkDestroyShaderModule(device, module, nullptr); // the pipeline keeps what it needs
    if (created != VK_SUCCESS) return vk_failure("vkCreateComputePipelines", created);
    k->creation_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return k;
}

Kernel::~Kernel() {
    vkDestroyPipeline(device_, pipeline_, nullptr);
    vkDestroyPipelineLayout(device_, layout_, nullptr);
    vkDestroyDescriptorSetLayout(device_, set_layout_, nullptr);
}

} // namespace kdop
