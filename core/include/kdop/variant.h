// The registry of embedded k-DOP clipping variants and a project's own shaders: what
// kdop_add_variants() generates for a target and what a caller needs to build a pipeline without
// guessing (kdop/vulkan_pipeline.h builds it). Plain data, C++17, no dependencies (not even Vulkan's
// headers: stages and formats are Vulkan's numbers), so a renderer can include it as is.
//
// Each variant's compute shader reads the current frame and the history (two combined image
// samplers, read with texelFetch, so any float format works), clips the history to the k-DOP of
// the current frame's neighborhood (clamp-to-edge) and writes the result to an rgba32f storage
// image. Dispatch ceil(width / local_size[0]) x ceil(height / local_size[1]) workgroups.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace kdop {

enum class Mode : std::uint8_t {
    clip,    // slabs span the neighborhood's min..max (the paper's k-DOP clip)
    varclip, // slabs span mean +- gamma * sigma (variance clip; gamma is a push constant)
    // Cost baselines, not clips (no axis set): `gather` reads the neighborhood and history as a
    // clip variant does and writes their sum; `copy` writes the history as it is.
    gather,
    copy,
    // A project's own shader (kdop_add_variants SHADERS: compute, vertex or fragment), compiled with
    // the kdop functions it includes; named after its file, with no axis set or neighborhood of its own.
    shader,
};

// How a clip is written. Both compute the same function; `loop` is the supplement's form (axes in
// a constant array, loops over axes and neighbors), kept as a baseline for tests and benchmarks.
enum class Form : std::uint8_t {
    unrolled,
    loop,
};

// What a clip computes at the numerical extremes (HDR, flat neighborhoods, NaN or Inf history).
// Unlike Form, this changes the function: `paper` is the supplement's formulation as written;
// `hardened` (the default) pads slabs by the pixel's magnitude, takes the variance of colors
// relative to the pixel and replaces an unusable history by the current color (docs/clip.md,
// "Numerics at the extremes"). Variants with the paper's numerics are named <variant>-paper.
enum class Numerics : std::uint8_t {
    hardened,
    paper,
};

enum class Neighborhood : std::uint8_t {
    n9, // 3x3, row-major, the pixel itself at index 4
    n5, // plus shape: up, left, self, right, down (the pixel itself at index 2)
};

// The stage of an entry's module. Variants are compute shaders; a project's SHADERS may be any of
// these, by their file's extension (.comp, .vert, .frag, as glslc reads them).
enum class ShaderStage : std::uint8_t {
    compute,  // VK_SHADER_STAGE_COMPUTE_BIT
    vertex,   // VK_SHADER_STAGE_VERTEX_BIT
    fragment, // VK_SHADER_STAGE_FRAGMENT_BIT
};

enum class DescriptorType : std::uint8_t {
    combined_image_sampler, // VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER: sampler2D
    storage_image,          // VK_DESCRIPTOR_TYPE_STORAGE_IMAGE: image2D
    sampled_image,          // VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE: texture2D (HLSL's Texture2D)
    sampler,                // VK_DESCRIPTOR_TYPE_SAMPLER: sampler (HLSL's SamplerState)
    uniform_texel_buffer,   // VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER: samplerBuffer, textureBuffer
    storage_texel_buffer,   // VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER: imageBuffer
    uniform_buffer,         // VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER: uniform blocks (HLSL's cbuffer)
    storage_buffer,         // VK_DESCRIPTOR_TYPE_STORAGE_BUFFER: buffer blocks
};

struct DescriptorBinding {
    std::uint32_t set;
    std::uint32_t binding;
    DescriptorType type;
    const char* name;         // as the shader's code names it, GLSL or HLSL: the variable; a block's instance
                              // (`uniform B {...} b;`, `ConstantBuffer<B> b`), or without one its block
                              // (`uniform B {...};`, `cbuffer B`): b, b, B, B (docs/embedding.md#binding-names)
    std::uint32_t count;      // descriptors in the binding: 1, or the array's length (uniform sampler2D t[4])
    std::uint32_t stages;     // VkShaderStageFlags of the entry's stage
    std::uint32_t block_size; // buffers: the block's size in bytes, a trailing runtime array not counted; else 0
    std::uint32_t format;     // storage images and texel buffers: the VkFormat the shader declares
                              // (rgba32f: 109, VK_FORMAT_R32G32B32A32_SFLOAT); 0 when it declares none
};

// One member of the push-constant block, in the entry's stage. All of an entry's members together
// form one range starting at offset 0 of push_constant_size bytes.
struct PushConstantMember {
    const char* name;
    std::uint32_t offset;
    std::uint32_t size;
};

struct Variant {
    const char* name;     // "<set>-<mode>-<neighborhood>[-loop][-paper]", e.g. "dop32-clip-n9"; "gather-n9"; "copy"
    const char* axis_set; // e.g. "dop32"; "" for the gather and copy baselines
    Mode mode;
    Neighborhood neighborhood;
    Form form;
    Numerics numerics;
    std::uint32_t axis_count; // k / 2

    const std::uint32_t* spirv; // optimized, validated SPIR-V words (shared by identical variants)
    std::size_t spirv_word_count;
    std::uint64_t spirv_hash; // FNV-1a 64 of the SPIR-V bytes: equal hashes, same module

    const char* entry_point;
    std::uint32_t local_size[3];
    const DescriptorBinding* bindings;
    std::uint32_t binding_count;
    const PushConstantMember* push_constants;
    std::uint32_t push_constant_count;
    std::uint32_t push_constant_size; // bytes; 0 when the variant takes none

    ShaderStage stage;                // compute for every variant; local_size is 0 for the other stages
    std::uint32_t color_output_count; // fragment shaders: color attachments written (highest location + 1)
};

// Where a TAA resolve clips and blends: colors as they are, raised to an exponent, or log(c + 1e-5)
// (kdop's --color-map linear, gamma:G, log).
enum class ColorMapKind : std::uint8_t {
    linear,
    power,
    log,
};

// How a resolve samples the history at the reprojected position (--history-filter).
enum class HistoryFilter : std::uint8_t {
    bilinear,
    catmull_rom, // the 4x4 Catmull-Rom cubic
};

// How an upscaling resolve reconstructs each output pixel's current color from the input samples
// around it (--upscale-filter): Lanczos-2 clamped to the neighborhood's range (FSR 2's), or a
// Gaussian of standard deviation 0.5 input pixels.
enum class UpscaleFilter : std::uint8_t {
    lanczos2,
    gaussian,
};

// How an upscaling resolve widens the variance clip with the ratio r (--upscale-box-scale): not at
// all, or gamma times 1 + (r - 1) / 2, as FSR 2.0 widens its box.
enum class BoxScale : std::uint8_t {
    none,
    fsr2,
};

// Which of the nearest input sample's neighbors an upscaling resolve's clip keeps
// (--upscale-sample-distance): all, those within a fixed distance of the output pixel's center, or
// within UE4's (TemporalAA.usf's HISTORY_CLAMPING_BOX_SAMPLE_DISTANCE). A neighbor farther away
// stands in as the center sample.
struct SampleDistance {
    enum class Kind : std::uint8_t { all, ue4, fixed } kind = Kind::all;
    float pixels = 0; // Kind::fixed: the distance in input pixels
    // The distance at upscaling ratio `ratio`, in input pixels: fixed's, UE4's lerp(1.51, 1.3,
    // ratio - 1), or for all one no neighbor of a 3x3 lies beyond.
    constexpr float at(float ratio) const {
        return kind == Kind::fixed ? pixels : kind == Kind::ue4 ? 1.51f + (1.3f - 1.51f) * (ratio - 1.0f) : 1e30f;
    }
};

// The TAA resolve a manifest's variants were measured with: `kdop choose` records it in the
// kdop.manifest it writes (gamma:, current-weight:, color-map:, history-filter: and dilate-motion:
// lines), and kdop_add_variants(MANIFEST) declares it in the registry's header as
// `resolve_settings`. Build the resolve with these, give a varclip variant `gamma` as its push
// constant, and the figures the variant was chosen by hold for your resolve too.
struct ResolveSettings {
    float gamma;                  // the variance clip's width in standard deviations
    float current_weight;         // the current frame's share of the blend
    ColorMapKind color_map;       // the space the clip and the blend happen in
    double color_map_exponent;    // ColorMapKind::power: each color channel raised to it; otherwise 1
    HistoryFilter history_filter; // how the history is sampled
    bool dilate_motion;           // the motion of the nearest of the 3x3 neighbors by depth, not the pixel's own
    // Where the variants were judged on frames the resolve upscaled (the manifest's upscale-filter:,
    // upscale-sample-distance: and upscale-box-scale: lines): how it upscaled.
    bool upscaling = false;
    UpscaleFilter upscale_filter = UpscaleFilter::lanczos2;
    SampleDistance sample_distance = {};
    BoxScale box_scale = BoxScale::none;
};

struct VariantList {
    const Variant* first;
    std::size_t count;
    const Variant* begin() const { return first; }
    const Variant* end() const { return first + count; }
    std::size_t size() const { return count; }

    // The variant called `name`, or nullptr.
    const Variant* find(const char* name) const {
        for (const Variant& v : *this)
            if (std::strcmp(v.name, name) == 0) return &v;
        return nullptr;
    }
};

inline const char* to_string(Mode mode) {
    switch (mode) {
    case Mode::clip: return "clip";
    case Mode::varclip: return "varclip";
    case Mode::gather: return "gather";
    case Mode::copy: return "copy";
    case Mode::shader: return "shader";
    }
    return "?";
}
inline const char* to_string(ShaderStage stage) {
    switch (stage) {
    case ShaderStage::compute: return "compute";
    case ShaderStage::vertex: return "vertex";
    case ShaderStage::fragment: return "fragment";
    }
    return "?";
}
inline const char* to_string(DescriptorType type) {
    switch (type) {
    case DescriptorType::combined_image_sampler: return "combined image sampler";
    case DescriptorType::storage_image: return "storage image";
    case DescriptorType::sampled_image: return "sampled image";
    case DescriptorType::sampler: return "sampler";
    case DescriptorType::uniform_texel_buffer: return "uniform texel buffer";
    case DescriptorType::storage_texel_buffer: return "storage texel buffer";
    case DescriptorType::uniform_buffer: return "uniform buffer";
    case DescriptorType::storage_buffer: return "storage buffer";
    }
    return "?";
}
// VkShaderStageFlagBits of `stage`.
inline std::uint32_t vulkan_stage_bit(ShaderStage stage) {
    switch (stage) {
    case ShaderStage::compute: return 0x20;  // VK_SHADER_STAGE_COMPUTE_BIT
    case ShaderStage::vertex: return 0x01;   // VK_SHADER_STAGE_VERTEX_BIT
    case ShaderStage::fragment: return 0x10; // VK_SHADER_STAGE_FRAGMENT_BIT
    }
    return 0;
}
// "bilinear", "catmull-rom": as --history-filter and a manifest's history-filter: line spell it.
inline const char* to_string(HistoryFilter filter) {
    return filter == HistoryFilter::catmull_rom ? "catmull-rom" : "bilinear";
}

inline const char* to_string(UpscaleFilter filter) {
    return filter == UpscaleFilter::gaussian ? "gaussian" : "lanczos2";
}

inline const char* to_string(BoxScale scale) { return scale == BoxScale::fsr2 ? "fsr2" : "none"; }
inline const char* to_string(Form form) { return form == Form::unrolled ? "unrolled" : "loop"; }
inline const char* to_string(Numerics numerics) { return numerics == Numerics::hardened ? "hardened" : "paper"; }
inline const char* to_string(Neighborhood n) { return n == Neighborhood::n9 ? "n9" : "n5"; }

} // namespace kdop
