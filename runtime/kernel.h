// A compute pipeline for one registry variant, built from what the registry says about it: its
// SPIR-V, entry point, descriptor bindings and push-constant range. No guessing, no reflection
// at run time.
#pragma once

#include "context.h"

#include <kdop/variant.h>

#include <memory>

namespace kdop {

class Kernel {
public:
    static Result<std::unique_ptr<Kernel>> create(const Context& context, const Variant& variant);
    ~Kernel();
    Kernel(const Kernel&) = delete;
    Kernel& operator=(const Kernel&) = delete;

    const Variant& variant() const { return variant_; }
    VkDescriptorSetLayout set_layout() const { return set_layout_; }
    VkPipelineLayout layout() const { return layout_; }
    VkPipeline pipeline() const { return pipeline_; }
    // Wall time of shader-module and pipeline creation (the driver's compile), in milliseconds.
    double creation_ms() const { return creation_ms_; }

private:
    Kernel(const Context& context, const Variant& variant) : device_(context.device()), variant_(variant) {}

    VkDevice device_;
    const Variant& variant_;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    double creation_ms_ = 0;
};

} // namespace kdop
