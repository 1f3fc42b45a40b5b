#include "runtime/kernel.h"

#include "runtime/vulkan_error.h"

#include <fmt/format.h>

#include <chrono>

namespace kdop {

Result<std::unique_ptr<Kernel>> Kernel::create(const Context& context, const Variant& variant) {
    std::unique_ptr<Kernel> k(new Kernel(context));
    VkDevice device = context.device();
    k->name_ = variant.name;
    for (uint32_t i = 0; i < variant.binding_count; ++i)
        k->bindings_.push_back({variant.bindings[i].binding, variant.bindings[i].type, variant.bindings[i].name,
                                variant.bindings[i].format});
    for (uint32_t i = 0; i < variant.push_constant_count; ++i)
        k->push_constants_.push_back(
            {variant.push_constants[i].name, variant.push_constants[i].offset, variant.push_constants[i].size});
    k->push_constant_size_ = variant.push_constant_size;
    k->local_size_ = {variant.local_size[0], variant.local_size[1], variant.local_size[2]};

    if (variant.stage != ShaderStage::compute)
        return fail(fmt::format("{}: a {} shader; the runtime dispatches compute shaders", variant.name,
                                to_string(variant.stage)));
    for (uint32_t i = 0; i < variant.binding_count; ++i)
        if (variant.bindings[i].set != 0)
            return fail(fmt::format("{}: binding '{}' is in descriptor set {}; the runtime binds set 0 only",
                                    variant.name, variant.bindings[i].name, variant.bindings[i].set));

    // The same one call a renderer makes (kdop/vulkan_pipeline.h), so every GPU test exercises it.
    auto start = std::chrono::steady_clock::now();
    if (VkResult created = create_variant_pipeline(device, variant, k->pipeline_); created != VK_SUCCESS)
        return vk_failure("kdop::create_variant_pipeline", created);
    k->creation_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return k;
}

Kernel::~Kernel() { destroy_variant_pipeline(device_, pipeline_); }

} // namespace kdop
