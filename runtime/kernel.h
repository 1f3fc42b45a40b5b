// A compute pipeline for one registry variant, built from what the registry says about it: its
// SPIR-V, entry point, descriptor bindings and push-constant range. No guessing, no reflection
// at run time. The kernel copies what it needs of the variant, so it may outlive the registry
// entry (a variant built in-process and dropped before its kernel).
#pragma once

#include "runtime/context.h"

#include <kdop/variant.h>
#include <kdop/vulkan_pipeline.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace kdop {

class Kernel {
public:
    static Result<std::unique_ptr<Kernel>> create(const Context& context, const Variant& variant);
    ~Kernel();
    Kernel(const Kernel&) = delete;
    Kernel& operator=(const Kernel&) = delete;

    // The variant's interface, as the registry gave it.
    struct Binding {
        std::uint32_t binding;
        DescriptorType type;
        std::string name;
        std::uint32_t format; // a storage image's VkFormat as the shader declares it; else 0
    };
    struct PushConstant {
        std::string name;
        std::uint32_t offset, size;
    };
    const std::string& name() const { return name_; }
    const std::vector<Binding>& bindings() const { return bindings_; }
    const std::vector<PushConstant>& push_constants() const { return push_constants_; }
    std::uint32_t push_constant_size() const { return push_constant_size_; }
    const std::array<std::uint32_t, 3>& local_size() const { return local_size_; }
    VkDescriptorSetLayout set_layout() const { return pipeline_.set_layouts[0]; }
    VkPipelineLayout layout() const { return pipeline_.pipeline_layout; }
    VkPipeline pipeline() const { return pipeline_.pipeline; }
    // Wall time of shader-module and pipeline creation (the driver's compile), in milliseconds.
    double creation_ms() const { return creation_ms_; }

private:
    explicit Kernel(const Context& context) : device_(context.device()) {}

    VkDevice device_;
    std::string name_;
    std::vector<Binding> bindings_;
    std::vector<PushConstant> push_constants_;
    std::uint32_t push_constant_size_ = 0;
    std::array<std::uint32_t, 3> local_size_{};
    VariantPipeline pipeline_;
    double creation_ms_ = 0;
};

} // namespace kdop
