#include "generator/shader_reflection.h"

#include <fmt/format.h>
#include <spirv_cross/spirv_cross.hpp>

#include <algorithm>
#include <tuple>

namespace kdop {
namespace {

using spirv_cross::Compiler;
using spirv_cross::Resource;
using spirv_cross::SPIRType;

Result<ShaderStage> stage_of(spv::ExecutionModel model) {
    switch (model) {
    case spv::ExecutionModelGLCompute: return ShaderStage::compute;
    case spv::ExecutionModelVertex: return ShaderStage::vertex;
    case spv::ExecutionModelFragment: return ShaderStage::fragment;
    default: return fail("the entry point's stage is not one kdop builds pipelines for (compute, vertex, fragment)");
    }
}

// Descriptors in the binding: the product of the array's lengths, 1 for a single descriptor.
Result<std::uint32_t> descriptor_count(const SPIRType& type, const std::string& name) {
    std::uint32_t count = 1;
    for (std::size_t i = 0; i < type.array.size(); ++i) {
        if (!type.array_size_literal[i])
            return fail(fmt::format("resource '{}' is an array sized by a specialization constant, which kdop "
                                    "does not reflect",
                                    name));
        if (type.array[i] == 0)
            return fail(fmt::format("resource '{}' is a runtime-sized descriptor array (descriptor indexing), "
                                    "which kdop does not reflect",
                                    name));
        count *= type.array[i];
    }
    return count;
}

// The name the shader's code uses (BindingInfo::name): the variable's, or a block's name when the
// block has no instance name (GLSL's `uniform B { ... };`; glslang gives HLSL's `cbuffer B` no
// variable name either). Not r.name, which is a block's name even where it has an instance.
std::string resource_name(const Compiler& compiler, const Resource& r) {
    std::string name = compiler.get_name(r.id);
    return name.empty() ? compiler.get_name(r.base_type_id) : name;
}

Result<void> add_bindings(const Compiler& compiler, const spirv_cross::SmallVector<Resource>& resources,
                          DescriptorType type, ShaderInterface& out) {
    for (const Resource& r : resources) {
        const std::string name = resource_name(compiler, r);
        if (!compiler.has_decoration(r.id, spv::DecorationDescriptorSet) ||
            !compiler.has_decoration(r.id, spv::DecorationBinding))
            return fail(fmt::format("resource '{}' has no descriptor set or binding", name));
        const SPIRType& spirv_type = compiler.get_type(r.type_id);
        auto count = descriptor_count(spirv_type, name);
        if (!count) return std::unexpected(count.error());
        BindingInfo b{compiler.get_decoration(r.id, spv::DecorationDescriptorSet),
                      compiler.get_decoration(r.id, spv::DecorationBinding), type, name, *count};
        // An image whose dimension is Buffer is a texel buffer: Vulkan binds GLSL's samplerBuffer (a
        // combined image sampler in the SPIR-V) and textureBuffer as uniform texel buffers.
        const bool image = type == DescriptorType::combined_image_sampler || type == DescriptorType::sampled_image ||
                           type == DescriptorType::storage_image;
        const bool buffer_dim = image && spirv_type.image.dim == spv::DimBuffer;
        if (buffer_dim)
            b.type = type == DescriptorType::storage_image ? DescriptorType::storage_texel_buffer
                                                           : DescriptorType::uniform_texel_buffer;
        if (type == DescriptorType::storage_image || buffer_dim)
            b.format = vulkan_format_of_image_format(static_cast<std::uint32_t>(spirv_type.image.format));
        if (type == DescriptorType::uniform_buffer || type == DescriptorType::storage_buffer)
            b.block_size =
                static_cast<std::uint32_t>(compiler.get_declared_struct_size(compiler.get_type(r.base_type_id)));
        if (type == DescriptorType::uniform_buffer) {
            const SPIRType& block = compiler.get_type(r.base_type_id);
            for (std::uint32_t m = 0; m < block.member_types.size(); ++m)
                b.members.push_back({compiler.get_member_name(r.base_type_id, m),
                                     compiler.type_struct_member_offset(block, m),
                                     static_cast<std::uint32_t>(compiler.get_declared_struct_member_size(block, m))});
        }
        out.bindings.push_back(std::move(b));
    }
    return {};
}

Result<void> refuse(const Compiler& compiler, const spirv_cross::SmallVector<Resource>& resources,
                    std::string_view what) {
    if (resources.empty()) return {};
    return fail(
        fmt::format("resource '{}' is {}, which kdop does not reflect", resource_name(compiler, resources[0]), what));
}

Result<void> reflect_push_constants(const Compiler& compiler, const spirv_cross::SmallVector<Resource>& blocks,
                                    ShaderInterface& out) {
    if (blocks.size() > 1) return fail("module has more than one push-constant block");
    for (const Resource& r : blocks) {
        const SPIRType& block = compiler.get_type(r.base_type_id);
        for (std::uint32_t m = 0; m < block.member_types.size(); ++m) {
            const std::uint32_t offset = compiler.type_struct_member_offset(block, m);
            const auto size = static_cast<std::uint32_t>(compiler.get_declared_struct_member_size(block, m));
            out.push_constants.push_back({compiler.get_member_name(r.base_type_id, m), offset, size});
            out.push_constant_size = std::max(out.push_constant_size, offset + size);
        }
    }
    return {};
}

Result<std::array<std::uint32_t, 3>> workgroup_size(const Compiler& compiler, const spirv_cross::SPIREntryPoint& e) {
    std::array<std::uint32_t, 3> size{e.workgroup_size.x, e.workgroup_size.y, e.workgroup_size.z};
    // glslang writes the size as LocalSizeId for SPIR-V 1.6 (Vulkan 1.3): ids of constants.
    const std::array<std::uint32_t, 3> ids{e.workgroup_size.id_x, e.workgroup_size.id_y, e.workgroup_size.id_z};
    for (int i = 0; i < 3; ++i)
        if (size[i] == 0 && ids[i] != 0) size[i] = compiler.get_constant(ids[i]).scalar();
    if (size[0] == 0) return fail("compute entry point has no workgroup size");
    return size;
}

Result<ShaderInterface> reflect(const Compiler& compiler) {
    const auto entries = compiler.get_entry_points_and_stages();
    if (entries.empty()) return fail("module has no entry point");
    if (entries.size() > 1) return fail("module has more than one entry point");
    ShaderInterface out;
    auto stage = stage_of(entries[0].execution_model);
    if (!stage) return std::unexpected(stage.error());
    out.stage = *stage;
    out.entry_point = entries[0].name;
    if (out.stage == ShaderStage::compute) {
        auto size = workgroup_size(compiler, compiler.get_entry_point(entries[0].name, entries[0].execution_model));
        if (!size) return std::unexpected(size.error());
        out.local_size = *size;
    }

    const spirv_cross::ShaderResources resources = compiler.get_shader_resources();
    for (auto ok : {refuse(compiler, resources.acceleration_structures, "an acceleration structure"),
                    refuse(compiler, resources.atomic_counters, "an atomic counter"),
                    refuse(compiler, resources.subpass_inputs, "an input attachment (subpassInput)"),
                    refuse(compiler, resources.shader_record_buffers, "a shader record buffer"),
                    add_bindings(compiler, resources.sampled_images, DescriptorType::combined_image_sampler, out),
                    add_bindings(compiler, resources.storage_images, DescriptorType::storage_image, out),
                    add_bindings(compiler, resources.separate_images, DescriptorType::sampled_image, out),
                    add_bindings(compiler, resources.separate_samplers, DescriptorType::sampler, out),
                    add_bindings(compiler, resources.uniform_buffers, DescriptorType::uniform_buffer, out),
                    add_bindings(compiler, resources.storage_buffers, DescriptorType::storage_buffer, out),
                    reflect_push_constants(compiler, resources.push_constant_buffers, out)})
        if (!ok) return std::unexpected(ok.error());

    std::sort(out.bindings.begin(), out.bindings.end(), [](const BindingInfo& a, const BindingInfo& b) {
        return std::tie(a.set, a.binding) < std::tie(b.set, b.binding);
    });
    for (std::size_t i = 1; i < out.bindings.size(); ++i)
        if (out.bindings[i].set == out.bindings[i - 1].set && out.bindings[i].binding == out.bindings[i - 1].binding)
            return fail(fmt::format("resources '{}' and '{}' share set {} binding {}", out.bindings[i - 1].name,
                                    out.bindings[i].name, out.bindings[i].set, out.bindings[i].binding));

    if (out.stage == ShaderStage::fragment)
        for (const Resource& r : resources.stage_outputs)
            out.color_output_count =
                std::max(out.color_output_count, compiler.get_decoration(r.id, spv::DecorationLocation) + 1);
    return out;
}

} // namespace

Result<ShaderInterface> reflect_interface(std::span<const std::uint32_t> words) {
    // SPIRV-Cross reports what it cannot parse by throwing.
    try {
        const Compiler compiler(words.data(), words.size());
        return reflect(compiler);
    } catch (const spirv_cross::CompilerError& e) {
        return fail(fmt::format("SPIRV-Cross cannot read the module: {}", e.what()));
    }
}

std::uint32_t vulkan_format_of_image_format(std::uint32_t spirv_image_format) {
    // spv::ImageFormat 1..41 in order, to its VkFormat (vulkan_core.h), which has no such table itself.
    static constexpr std::uint32_t kVulkanFormats[] = {
        0,   // Unknown: the shader declares none (shaderStorageImage*WithoutFormat)
        109, // Rgba32f: R32G32B32A32_SFLOAT
        97,  // Rgba16f: R16G16B16A16_SFLOAT
        100, // R32f: R32_SFLOAT
        37,  // Rgba8: R8G8B8A8_UNORM
        38,  // Rgba8Snorm: R8G8B8A8_SNORM
        103, // Rg32f: R32G32_SFLOAT
        83,  // Rg16f: R16G16_SFLOAT
        122, // R11fG11fB10f: B10G11R11_UFLOAT_PACK32
        76,  // R16f: R16_SFLOAT
        91,  // Rgba16: R16G16B16A16_UNORM
        64,  // Rgb10A2: A2B10G10R10_UNORM_PACK32
        77,  // Rg16: R16G16_UNORM
        16,  // Rg8: R8G8_UNORM
        70,  // R16: R16_UNORM
        9,   // R8: R8_UNORM
        92,  // Rgba16Snorm: R16G16B16A16_SNORM
        78,  // Rg16Snorm: R16G16_SNORM
        17,  // Rg8Snorm: R8G8_SNORM
        71,  // R16Snorm: R16_SNORM
        10,  // R8Snorm: R8_SNORM
        108, // Rgba32i: R32G32B32A32_SINT
        96,  // Rgba16i: R16G16B16A16_SINT
        42,  // Rgba8i: R8G8B8A8_SINT
        99,  // R32i: R32_SINT
        102, // Rg32i: R32G32_SINT
        82,  // Rg16i: R16G16_SINT
        21,  // Rg8i: R8G8_SINT
        75,  // R16i: R16_SINT
        14,  // R8i: R8_SINT
        107, // Rgba32ui: R32G32B32A32_UINT
        95,  // Rgba16ui: R16G16B16A16_UINT
        41,  // Rgba8ui: R8G8B8A8_UINT
        98,  // R32ui: R32_UINT
        68,  // Rgb10a2ui: A2B10G10R10_UINT_PACK32
        101, // Rg32ui: R32G32_UINT
        81,  // Rg16ui: R16G16_UINT
        20,  // Rg8ui: R8G8_UINT
        74,  // R16ui: R16_UINT
        13,  // R8ui: R8_UINT
        110, // R64ui: R64_UINT
        111, // R64i: R64_SINT
    };
    return spirv_image_format < std::size(kVulkanFormats) ? kVulkanFormats[spirv_image_format] : 0;
}

} // namespace kdop
