// The resolves an engine writes (examples/engine_resolve): a compute resolve with a uniform buffer,
// a storage buffer, a separate texture and sampler, and a vertex + fragment resolve with an array
// of combined image samplers and a fragment push constant; and both again as HLSL ports (compiled
// by glslang's HLSL front end, their registers the bindings). Built into this binary with
// kdop_add_variants SHADERS (tests/CMakeLists.txt), their reflection is checked against the
// shaders' declarations, and both run through kdop/vulkan_pipeline.h, with a function table and
// VK_NO_PROTOTYPES (resolve_runner.cpp), on lavapipe with the validation layer on, against the CPU
// reference. The example's TAAU resolve, in both languages, runs against kdop's own upscaling resolve.
#include "examples/engine_resolve/resolve_runner.h"
#include "generator/shader_reflection.h"
#include "images/texture_cases.h"
#include "kdop_test_shaders.h"
#include "reference/cpu_clip.h"
#include "scenes/sprite_scene.h"
#include "sequence/jitter.h"
#include "temporal/resolve_bindings.h"
#include "temporal/taa_resolve.h"
#include "temporal/taa_shader.h"
#include "tests/gpu_support.h"

#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <spirv/unified1/spirv.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <span>
#include <string>
#include <tuple>

namespace kdop {
namespace {

constexpr std::uint32_t kWidth = 40, kHeight = 24; // not multiples of the 8x8 work group on both axes
constexpr std::uint64_t kSeed = 11;
constexpr double kTolerance = 2e-4; // taa_resolve_test.cpp's, for the same clip and content

const Variant& shader(const char* name) {
    const Variant* v = test_shaders::variants().find(name);
    if (!v) ADD_FAILURE() << name << " is not in the test registry";
    static const Variant none{};
    return v ? *v : none;
}

TEST(EngineShaders, ReflectsEveryBindingAsDeclared) {
    const Variant& compute = shader("resolve_compute");
    EXPECT_EQ(compute.stage, ShaderStage::compute);
    EXPECT_EQ(compute.local_size[0], 8u);
    EXPECT_EQ(compute.local_size[1], 8u);
    EXPECT_EQ(compute.push_constant_size, 0u);
    struct Expected {
        const char* name;
        std::uint32_t set, binding;
        DescriptorType type;
        std::uint32_t block_size, format;
    };
    const Expected compute_bindings[] = {
        {"current_texture", 0, 0, DescriptorType::sampled_image, 0, 0},
        {"nearest_sampler", 0, 1, DescriptorType::sampler, 0, 0},
        {"history_frame", 0, 2, DescriptorType::combined_image_sampler, 0, 0},
        {"resolved_frame", 0, 3, DescriptorType::storage_image, 0, 109}, // VK_FORMAT_R32G32B32A32_SFLOAT
        {"parameters", 1, 0, DescriptorType::uniform_buffer, 12, 0},     // vec2 + float, std140
        {"clip_distances", 1, 1, DescriptorType::storage_buffer, 0, 0},  // only a runtime array
    };
    ASSERT_EQ(compute.binding_count, std::size(compute_bindings));
    for (const Expected& e : compute_bindings) {
        const DescriptorBinding* b = find_binding(compute, e.name);
        ASSERT_NE(b, nullptr) << e.name;
        EXPECT_EQ(b->set, e.set) << e.name;
        EXPECT_EQ(b->binding, e.binding) << e.name;
        EXPECT_EQ(b->type, e.type) << e.name << ": " << to_string(b->type);
        EXPECT_EQ(b->count, 1u) << e.name;
        EXPECT_EQ(b->stages, 0x20u) << e.name; // VK_SHADER_STAGE_COMPUTE_BIT
        EXPECT_EQ(b->block_size, e.block_size) << e.name;
        EXPECT_EQ(b->format, e.format) << e.name;
    }

    const Variant& vertex = shader("fullscreen");
    EXPECT_EQ(vertex.stage, ShaderStage::vertex);
    EXPECT_EQ(vertex.binding_count, 0u);
    EXPECT_EQ(vertex.local_size[0], 0u);

    const Variant& fragment = shader("resolve_fragment");
    EXPECT_EQ(fragment.stage, ShaderStage::fragment);
    EXPECT_EQ(fragment.color_output_count, 1u);
    ASSERT_EQ(fragment.binding_count, 2u);
    const DescriptorBinding* frames = find_binding(fragment, "frames");
    ASSERT_NE(frames, nullptr);
    EXPECT_EQ(frames->type, DescriptorType::combined_image_sampler);
    EXPECT_EQ(frames->count, 2u);
    EXPECT_EQ(frames->stages, 0x10u); // VK_SHADER_STAGE_FRAGMENT_BIT
    const DescriptorBinding* parameters = find_binding(fragment, "parameters");
    ASSERT_NE(parameters, nullptr);
    EXPECT_EQ(parameters->type, DescriptorType::uniform_buffer);
    EXPECT_EQ(parameters->block_size, 8u);
    ASSERT_EQ(fragment.push_constant_count, 1u);
    EXPECT_STREQ(fragment.push_constants[0].name, "current_weight");
    EXPECT_EQ(fragment.push_constant_size, 4u);
}

// The HLSL ports: each register's number its binding and its space its set, Texture2D a sampled
// image, SamplerState a sampler, ConstantBuffer a uniform block with its size, RWTexture2D<float4>
// a storage image of rgba32f, RWStructuredBuffer a storage buffer, [[vk::push_constant]] the push
// constants.
TEST(EngineShaders, ReflectsTheHlslPortsRegistersAsBindings) {
    const Variant& compute = shader("hlsl_resolve_compute");
    EXPECT_EQ(compute.stage, ShaderStage::compute);
    EXPECT_STREQ(compute.entry_point, "main");
    EXPECT_EQ(compute.local_size[0], 8u);
    EXPECT_EQ(compute.local_size[1], 8u);
    EXPECT_EQ(compute.local_size[2], 1u);
    struct Expected {
        const char* name;
        std::uint32_t set, binding;
        DescriptorType type;
        std::uint32_t count, block_size, format;
    };
    const Expected compute_bindings[] = {
        {"current_texture", 0, 0, DescriptorType::sampled_image, 1, 0, 0},  // register(t0)
        {"nearest_sampler", 0, 1, DescriptorType::sampler, 1, 0, 0},        // register(s1)
        {"history_frame", 0, 2, DescriptorType::sampled_image, 1, 0, 0},    // register(t2)
        {"resolved_frame", 0, 3, DescriptorType::storage_image, 1, 0, 109}, // register(u3), float4: rgba32f
        {"history_sampler", 0, 4, DescriptorType::sampler, 1, 0, 0},        // [[vk::binding(4, 0)]]
        {"parameters", 1, 0, DescriptorType::uniform_buffer, 1, 12, 0},     // register(b0, space1)
        {"clip_distances", 1, 1, DescriptorType::storage_buffer, 1, 0, 0},  // register(u1, space1)
    };
    const Expected fragment_bindings[] = {
        {"frames", 0, 0, DescriptorType::sampled_image, 2, 0, 0}, // register(t0), two of them
        {"parameters", 0, 1, DescriptorType::uniform_buffer, 1, 8, 0},
        {"frame_samplers", 0, 2, DescriptorType::sampler, 2, 0, 0},
    };
    const Variant& fragment = shader("hlsl_resolve_fragment");
    for (const auto& [entry, expected, stage_bit] :
         {std::tuple{&compute, std::span<const Expected>(compute_bindings), 0x20u},
          std::tuple{&fragment, std::span<const Expected>(fragment_bindings), 0x10u}}) {
        ASSERT_EQ(entry->binding_count, expected.size()) << entry->name;
        for (const Expected& e : expected) {
            const DescriptorBinding* b = find_binding(*entry, e.name);
            ASSERT_NE(b, nullptr) << entry->name << ": " << e.name;
            EXPECT_EQ(b->set, e.set) << e.name;
            EXPECT_EQ(b->binding, e.binding) << e.name;
            EXPECT_EQ(b->type, e.type) << e.name << ": " << to_string(b->type);
            EXPECT_EQ(b->count, e.count) << e.name;
            EXPECT_EQ(b->stages, stage_bit) << e.name;
            EXPECT_EQ(b->block_size, e.block_size) << e.name;
            EXPECT_EQ(b->format, e.format) << e.name;
        }
    }
    EXPECT_EQ(fragment.stage, ShaderStage::fragment);
    EXPECT_EQ(fragment.color_output_count, 1u);
    ASSERT_EQ(fragment.push_constant_count, 1u);
    EXPECT_STREQ(fragment.push_constants[0].name, "current_weight");
    EXPECT_EQ(fragment.push_constant_size, 4u);
    const Variant& vertex = shader("hlsl_fullscreen");
    EXPECT_EQ(vertex.stage, ShaderStage::vertex);
    EXPECT_EQ(vertex.binding_count, 0u);
}

// The TAAU resolves: three textures (GLSL's sampler2D a combined image sampler, HLSL's Texture2D
// read with Load a sampled image), the rgba32f output, and 12 bytes of push constants (jitter and
// current weight).
TEST(EngineShaders, ReflectsTheUpscalersTexturesAndPushConstants) {
    for (const auto& [name, texture_type] : {std::pair{"upscale_compute", DescriptorType::combined_image_sampler},
                                             std::pair{"hlsl_upscale_compute", DescriptorType::sampled_image}}) {
        const Variant& upscale = shader(name);
        EXPECT_EQ(upscale.stage, ShaderStage::compute) << name;
        EXPECT_EQ(upscale.local_size[0], 8u) << name;
        EXPECT_EQ(upscale.local_size[1], 8u) << name;
        ASSERT_EQ(upscale.binding_count, 4u) << name;
        const char* textures[] = {"current_frame", "motion_frame", "history_frame"};
        for (std::uint32_t i = 0; i < 3; ++i) {
            const DescriptorBinding* b = find_binding(upscale, textures[i]);
            ASSERT_NE(b, nullptr) << name << ": " << textures[i];
            EXPECT_EQ(b->set, 0u);
            EXPECT_EQ(b->binding, i) << name << ": " << textures[i];
            EXPECT_EQ(b->type, texture_type) << name << ": " << to_string(b->type);
        }
        const DescriptorBinding* output = find_binding(upscale, "resolved_frame");
        ASSERT_NE(output, nullptr) << name;
        EXPECT_EQ(output->binding, 3u);
        EXPECT_EQ(output->type, DescriptorType::storage_image);
        EXPECT_EQ(output->format, 109u); // VK_FORMAT_R32G32B32A32_SFLOAT
        EXPECT_EQ(upscale.push_constant_size, 12u) << name;
    }
}

// The bindings map shipped beside each TAAU resolve (examples/engine_resolve/*.bindings.json, for
// kdop taa --resolve-bindings) binds every texture, the output and both push constants of the
// shader as the registry reflects it.
TEST(EngineShaders, EachUpscalersBindingsMapBindsItsShader) {
    for (const char* name : {"upscale_compute", "hlsl_upscale_compute"}) {
        SCOPED_TRACE(name);
        const std::filesystem::path file = std::filesystem::path(KDOP_SOURCE_DIR) / "examples" / "engine_resolve" /
                                           (std::string(name) + ".bindings.json");
        auto map = read_resolve_bindings(file);
        ASSERT_TRUE(map) << map.error().message;
        auto bound = bind(*map, shader(name));
        ASSERT_TRUE(bound) << bound.error().message;
        EXPECT_EQ(bound->resources.size(), 4u);
        EXPECT_EQ(bound->values.size(), 2u);
        EXPECT_STREQ(bound->find(ResourceRole::output)->name, "resolved_frame");
    }
}

// The registry's storage formats are Vulkan's numbers, written in shader_reflection.cpp without
// Vulkan's headers; here each is checked against vulkan_core.h's enum, for every SPIR-V format.
TEST(EngineShaders, StorageFormatsAreVulkansNumbers) {
    const std::pair<spv::ImageFormat, VkFormat> formats[] = {
        {spv::ImageFormatUnknown, VK_FORMAT_UNDEFINED},
        {spv::ImageFormatRgba32f, VK_FORMAT_R32G32B32A32_SFLOAT},
        {spv::ImageFormatRgba16f, VK_FORMAT_R16G16B16A16_SFLOAT},
        {spv::ImageFormatR32f, VK_FORMAT_R32_SFLOAT},
        {spv::ImageFormatRgba8, VK_FORMAT_R8G8B8A8_UNORM},
        {spv::ImageFormatRgba8Snorm, VK_FORMAT_R8G8B8A8_SNORM},
        {spv::ImageFormatRg32f, VK_FORMAT_R32G32_SFLOAT},
        {spv::ImageFormatRg16f, VK_FORMAT_R16G16_SFLOAT},
        {spv::ImageFormatR11fG11fB10f, VK_FORMAT_B10G11R11_UFLOAT_PACK32},
        {spv::ImageFormatR16f, VK_FORMAT_R16_SFLOAT},
        {spv::ImageFormatRgba16, VK_FORMAT_R16G16B16A16_UNORM},
        {spv::ImageFormatRgb10A2, VK_FORMAT_A2B10G10R10_UNORM_PACK32},
        {spv::ImageFormatRg16, VK_FORMAT_R16G16_UNORM},
        {spv::ImageFormatRg8, VK_FORMAT_R8G8_UNORM},
        {spv::ImageFormatR16, VK_FORMAT_R16_UNORM},
        {spv::ImageFormatR8, VK_FORMAT_R8_UNORM},
        {spv::ImageFormatRgba16Snorm, VK_FORMAT_R16G16B16A16_SNORM},
        {spv::ImageFormatRg16Snorm, VK_FORMAT_R16G16_SNORM},
        {spv::ImageFormatRg8Snorm, VK_FORMAT_R8G8_SNORM},
        {spv::ImageFormatR16Snorm, VK_FORMAT_R16_SNORM},
        {spv::ImageFormatR8Snorm, VK_FORMAT_R8_SNORM},
        {spv::ImageFormatRgba32i, VK_FORMAT_R32G32B32A32_SINT},
        {spv::ImageFormatRgba16i, VK_FORMAT_R16G16B16A16_SINT},
        {spv::ImageFormatRgba8i, VK_FORMAT_R8G8B8A8_SINT},
        {spv::ImageFormatR32i, VK_FORMAT_R32_SINT},
        {spv::ImageFormatRg32i, VK_FORMAT_R32G32_SINT},
        {spv::ImageFormatRg16i, VK_FORMAT_R16G16_SINT},
        {spv::ImageFormatRg8i, VK_FORMAT_R8G8_SINT},
        {spv::ImageFormatR16i, VK_FORMAT_R16_SINT},
        {spv::ImageFormatR8i, VK_FORMAT_R8_SINT},
        {spv::ImageFormatRgba32ui, VK_FORMAT_R32G32B32A32_UINT},
        {spv::ImageFormatRgba16ui, VK_FORMAT_R16G16B16A16_UINT},
        {spv::ImageFormatRgba8ui, VK_FORMAT_R8G8B8A8_UINT},
        {spv::ImageFormatR32ui, VK_FORMAT_R32_UINT},
        {spv::ImageFormatRgb10a2ui, VK_FORMAT_A2B10G10R10_UINT_PACK32},
        {spv::ImageFormatRg32ui, VK_FORMAT_R32G32_UINT},
        {spv::ImageFormatRg16ui, VK_FORMAT_R16G16_UINT},
        {spv::ImageFormatRg8ui, VK_FORMAT_R8G8_UINT},
        {spv::ImageFormatR16ui, VK_FORMAT_R16_UINT},
        {spv::ImageFormatR8ui, VK_FORMAT_R8_UINT},
        {spv::ImageFormatR64ui, VK_FORMAT_R64_UINT},
        {spv::ImageFormatR64i, VK_FORMAT_R64_SINT},
    };
    ASSERT_EQ(std::size(formats), 42u) << "every SPIR-V image format up to R64i";
    for (const auto& [spirv, vulkan] : formats)
        EXPECT_EQ(vulkan_format_of_image_format(spirv), std::uint32_t(vulkan)) << "spv::ImageFormat " << int(spirv);
    EXPECT_EQ(vulkan_format_of_image_format(1000), 0u) << "a format the table does not know";
}

std::vector<float> floats_of(const Image& image) {
    std::vector<float> out;
    out.reserve(image.pixels.size() * 4);
    for (const glm::vec4& p : image.pixels) out.insert(out.end(), {p.r, p.g, p.b, p.a});
    return out;
}

Image image_of(const std::vector<float>& floats) {
    Image out(kWidth, kHeight);
    for (std::size_t i = 0; i < out.pixels.size(); ++i)
        out.pixels[i] = {floats[4 * i], floats[4 * i + 1], floats[4 * i + 2], floats[4 * i + 3]};
    return out;
}

// The TAAU resolve an engine writes (upscale_compute.comp, hlsl_upscale_compute.cs.hlsl), run by
// engine::Upscaler, against kdop's own upscaling resolve (TaaResolve with options.upscale, the same
// clip): a moving 2-D scene drawn at 32x20 with a Halton jitter, upscaled 2x over eight frames,
// each resolve from its own history. Float rounding apart (a history within rounding of a slab may
// land on either side, and then differs in the frames after), the three agree.
using EngineUpscaleGpu = test::ValidationChecked;

TEST_F(EngineUpscaleGpu, GlslAndHlslMatchKdopsUpscalingResolve) {
    constexpr std::uint32_t w = 32, h = 20, out_w = 64, out_h = 40;
    const engine::Device device{test::gpu().instance(), test::gpu().physical_device(), test::gpu().device(),
                                test::gpu().queue(),    test::gpu().queue_family(),    vkGetInstanceProcAddr};
    const SceneFrames frames("grass", make_texture(TextureFamily::grass, w, h, 3), 8, true, false);
    const std::uint32_t phases = upscale_jitter_phases(2);

    ResolveOptions options;
    options.upscale = true;
    auto kdop_shader = build_taa_shader({*resolve_axis_set("dop22"), Mode::clip, Neighborhood::n9}, options);
    ASSERT_TRUE(kdop_shader) << kdop_shader.error().message;
    const Variant* kdop_shaders[] = {&(*kdop_shader)->variant()};
    auto kdop_resolve = TaaResolve::create(test::gpu(), kdop_shaders, w, h, out_w, out_h, options);
    ASSERT_TRUE(kdop_resolve) << kdop_resolve.error().message;

    std::string error;
    std::unique_ptr<engine::Upscaler> upscalers[2];
    const char* names[2] = {"upscale_compute", "hlsl_upscale_compute"};
    for (int l = 0; l < 2; ++l) {
        upscalers[l] = engine::Upscaler::create(device, shader(names[l]), w, h, out_w, out_h, error);
        ASSERT_TRUE(upscalers[l]) << names[l] << ": " << error;
    }

    constexpr float kRounding = 1e-4f; // per pixel, the distance of two colors in [0, 1]
    const auto pixels_apart = [](const std::vector<float>& a, const std::vector<float>& b, float& largest) {
        std::size_t apart = 0;
        for (std::size_t i = 0; i < a.size(); i += 4) {
            const float d = glm::distance(glm::vec3(a[i], a[i + 1], a[i + 2]), glm::vec3(b[i], b[i + 1], b[i + 2]));
            largest = std::max(largest, d);
            if (d > kRounding) ++apart;
        }
        return apart;
    };
    const std::size_t pixels = std::size_t(out_w) * out_h;
    std::size_t most_apart = 0, most_apart_between = 0;
    float largest = 0, largest_between = 0;
    for (std::size_t f = 0; f < frames.frame_count(); ++f) {
        auto frame = frames.frame(f);
        ASSERT_TRUE(frame);
        frame->jitter = halton_jitter(std::uint32_t(f), phases);
        auto expected_image = (*kdop_resolve)->advance(*frame, frames.starts_history(f));
        ASSERT_TRUE(expected_image) << expected_image.error().message;
        const std::vector<float> expected = floats_of(**expected_image);

        engine::UpscaleFrames in;
        in.current = floats_of(frame->color);
        in.motion.assign(std::size_t(w) * h * 2, 0.0f);
        for (std::size_t i = 0; i < frame->motion.size(); ++i) {
            in.motion[2 * i] = frame->motion[i].x;
            in.motion[2 * i + 1] = frame->motion[i].y;
        }
        in.jitter = {frame->jitter.x, frame->jitter.y};
        in.current_weight = frames.starts_history(f) ? 1.0f : options.current_weight;
        std::vector<float> outputs[2];
        for (int l = 0; l < 2; ++l) {
            ASSERT_EQ(upscalers[l]->resolve(in, outputs[l]), "") << names[l] << ", frame " << f;
            ASSERT_EQ(outputs[l].size(), expected.size());
            const std::size_t apart = pixels_apart(outputs[l], expected, largest);
            EXPECT_LE(apart, pixels / 500) << names[l] << " against kdop's resolve, frame " << f;
            most_apart = std::max(most_apart, apart);
        }
        const std::size_t apart = pixels_apart(outputs[0], outputs[1], largest_between);
        EXPECT_LE(apart, pixels / 500) << "GLSL against HLSL, frame " << f;
        most_apart_between = std::max(most_apart_between, apart);
    }
    std::cout << "engine TAAU, " << pixels << " pixels a frame: against kdop's upscaling resolve at most " << most_apart
              << " apart by more than " << kRounding << ", largest difference " << largest
              << "; GLSL against HLSL at most " << most_apart_between << ", largest " << largest_between << "\n";

    engine::UpscaleFrames wrong_size;
    std::vector<float> unused;
    EXPECT_NE(upscalers[0]->resolve(wrong_size, unused).find("32x20 input"), std::string::npos);
}

// The resolves in GLSL ("") and their HLSL ports ("hlsl_"), by the prefix of their registry names.
class EngineResolveGpu : public test::ValidationChecked, public ::testing::WithParamInterface<const char*> {};

TEST_P(EngineResolveGpu, ComputeAndFragmentResolvesMatchTheReference) {
    ASSERT_TRUE(test::gpu().queue_flags() & VK_QUEUE_GRAPHICS_BIT) << "the test device's queue cannot draw";
    const engine::Device device{test::gpu().instance(), test::gpu().physical_device(), test::gpu().device(),
                                test::gpu().queue(),    test::gpu().queue_family(),    vkGetInstanceProcAddr};
    const std::string prefix = GetParam();
    const engine::Shaders shaders{&shader((prefix + "resolve_compute").c_str()),
                                  &shader((prefix + "fullscreen").c_str()),
                                  &shader((prefix + "resolve_fragment").c_str())};
    std::string error;
    auto resolver = engine::Resolver::create(device, shaders, kWidth, kHeight, error);
    ASSERT_TRUE(resolver) << error;
    auto dop22 = resolve_axis_set("dop22");
    ASSERT_TRUE(dop22);

    const glm::ivec2 motion(2, -3);
    const float weight = 0.125f;
    std::size_t checked = 0;
    for (const TestCase& c : make_test_cases(kWidth, kHeight, kSeed)) {
        engine::Frames frames{floats_of(c.current), floats_of(c.history), {float(motion.x), float(motion.y)}, weight};
        engine::Resolved resolved;
        ASSERT_EQ(resolver->resolve(frames, resolved), "") << c.name();

        Image reprojected(kWidth, kHeight);
        for (std::uint32_t y = 0; y < kHeight; ++y)
            for (std::uint32_t x = 0; x < kWidth; ++x)
                reprojected.at(x, y) = c.history.clamped(int(x) - motion.x, int(y) - motion.y);
        const Image clipped = reference_rectify(*dop22, Mode::clip, Neighborhood::n9, c.current, reprojected, 1.0);
        Image expected = clipped;
        for (std::size_t i = 0; i < expected.pixels.size(); ++i)
            expected.pixels[i] =
                glm::vec4(glm::mix(glm::vec3(clipped.pixels[i]), glm::vec3(c.current.pixels[i]), weight), 1);

        for (auto [what, floats] :
             {std::pair{"compute", &resolved.compute}, std::pair{"fragment", &resolved.fragment}}) {
            auto e = test::relative_error(image_of(*floats), expected, c.current, reprojected);
            EXPECT_LE(e.max_relative, kTolerance) << what << " resolve, " << c.name() << " at " << e.x << "," << e.y;
        }
        // The storage buffer: how far the clip moved each pixel's history.
        double worst = 0;
        for (std::size_t i = 0; i < clipped.pixels.size(); ++i) {
            const double d = glm::distance(glm::vec3(reprojected.pixels[i]), glm::vec3(clipped.pixels[i]));
            const double magnitude = std::max({1.0, double(glm::length(glm::vec3(reprojected.pixels[i]))),
                                               double(glm::length(glm::vec3(c.current.pixels[i])))});
            worst = std::max(worst, std::abs(resolved.clip_distance[i] - d) / magnitude);
        }
        EXPECT_LE(worst, 2 * kTolerance) << "clip distances, " << c.name();
        ++checked;
    }
    EXPECT_GE(checked, 24u);

    engine::Frames wrong_size{std::vector<float>(4), std::vector<float>(4)};
    engine::Resolved unused;
    EXPECT_NE(resolver->resolve(wrong_size, unused).find("40x24"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Languages, EngineResolveGpu, ::testing::Values("", "hlsl_"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                             return std::string(info.param).empty() ? std::string("Glsl") : std::string("Hlsl");
                         });

} // namespace
} // namespace kdop
