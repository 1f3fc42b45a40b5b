// Reflection of a shader module's interface, what a caller needs to build its pipeline: the entry
// point and stage, the workgroup size, every descriptor binding (type, array length, buffer block
// size, storage format), the push-constant members and a fragment shader's color outputs. Taken
// from the optimized module, the code that ships, so it cannot drift from it, and with SPIRV-Cross,
// the reflection RenderDoc and engines use, rather than a walk of our own.
#pragma once

#include "core/result.h"

#include <kdop/variant.h>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace kdop {

struct BindingInfo {
    std::uint32_t set;
    std::uint32_t binding;
    DescriptorType type;
    // The name the shader's code uses, one rule for GLSL and HLSL: the variable's; for a block, its
    // instance name (GLSL `uniform B { ... } b;`, HLSL `ConstantBuffer<B> b`: "b"), or where it has
    // none its block name (GLSL `uniform B { ... };`, HLSL `cbuffer B`: "B"). Not SPIRV-Cross's
    // Resource::name, the block's name: glslang's SPIR-V of `ConstantBuffer<B> b` has no B, so a
    // GLSL block and its HLSL port would differ. docs/embedding.md#binding-names.
    std::string name;
    std::uint32_t count = 1;      // array length; 1 for a single descriptor
    std::uint32_t block_size = 0; // buffers: declared block size in bytes
    std::uint32_t format = 0;     // storage images and texel buffers: VkFormat value, 0 if none declared
    // Uniform blocks: each member's name, offset and size (what kdop taa --resolve fills by role;
    // not in the registry, which records the block's size alone).
    struct Member {
        std::string name;
        std::uint32_t offset, size;
    };
    std::vector<Member> members = {};
};

struct PushConstantInfo {
    std::string name;
    std::uint32_t offset;
    std::uint32_t size;
};

struct ShaderInterface {
    ShaderStage stage = ShaderStage::compute;
    std::string entry_point;
    std::array<std::uint32_t, 3> local_size{}; // compute only
    std::vector<BindingInfo> bindings;         // sorted by set, then binding
    std::vector<PushConstantInfo> push_constants;
    std::uint32_t push_constant_size = 0;
    std::uint32_t color_output_count = 0; // fragment only: highest output location + 1
};

// Reflects a module with one compute, vertex or fragment entry point. Names come from OpName, so
// reflect before names are stripped. What the source declares and the entry point does not use is
// not in the module, so not here (unused_resources.h says what). Fails, naming the resource, for
// what kdop does not reflect: other stages, acceleration structures, atomic counters, input
// attachments, runtime-sized descriptor arrays, resources without a set or binding.
Result<ShaderInterface> reflect_interface(std::span<const std::uint32_t> words);

// The VkFormat value of a SPIR-V image format (spv::ImageFormat), 0 for Unknown.
std::uint32_t vulkan_format_of_image_format(std::uint32_t spirv_image_format);

} // namespace kdop
