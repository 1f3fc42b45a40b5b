// A renderer's own resolve measured through kdop's path (kdop taa --resolve): bound by the roles
// its map declares, built once per variant, run as kdop runs its own. kdop's resolve given as a
// renderer's resolves bit for bit as itself; the engine example's upscalers agree with it; a
// resolve that differs where it matters (YCoCg, a luminance weight, separate textures, UV motion)
// matches its CPU restatement; and what cannot be measured is refused, nothing written.
#include "core/read_file.h"
#include "generator/variant_spec.h"
#include "images/image_io.h"
#include "images/texture_cases.h"
#include "reference/cpu_clip.h"
#include "scenes/sprite_scene.h"
#include "sequence/jitter.h"
#include "temporal/own_resolve.h"
#include "temporal/taa_resolve.h"
#include "temporal/taa_shader.h"
#include "tests/gpu_support.h"
#include "tests/test_support.h"

#include <kdop/resolve_runner.h>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace kdop {
namespace {

std::filesystem::path source_file(const std::string& relative) {
    return std::filesystem::path(KDOP_SOURCE_DIR) / relative;
}

void write_text(const std::filesystem::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
}

// kdop's resolve as a renderer's own: a copy of the template with its options' defines beside it.
std::filesystem::path kdops_resolve_as_own(const std::filesystem::path& dir, const ResolveOptions& options) {
    auto text = read_input_file(source_file("shader_templates/taa_resolve.comp.in"));
    EXPECT_TRUE(text);
    write_text(dir / "taa_resolve.comp", text.value_or(""));
    write_text(dir / "resolve_options.glsl", resolve_option_defines(options));
    return dir / "taa_resolve.comp";
}

// The map of the template at its input size (the shipped one, shader_templates/
// taa_resolve.bindings.json, is for its upscaling build, which also takes the jitter and the
// sample distance).
constexpr const char* kNativeMap = R"({"format": "kdop-resolve-bindings", "version": 1,
 "resources": {"color_frame": "current", "history_frame": "history", "motion_frame": "motion",
               "rectified_history": "output"},
 "push_constants": {"current_weight": "current_weight", "gamma": "gamma"},
 "motion": {"units": "pixels", "points_to": "previous", "y_axis": "down"}})";

VariantSpec spec_of(const char* set, Mode mode, Neighborhood n = Neighborhood::n9) {
    auto axes = resolve_axis_set(set);
    EXPECT_TRUE(axes) << set;
    return {axes.value_or(AxisSet{}), mode, n};
}

bool same_bits(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec4)) == 0;
}

using OwnResolveGpu = test::ValidationChecked;

// Each variant's resolve twice in one TaaResolve, kdop's and the same shader given as a
// renderer's (bound by its map, its push constants by role): every output of every frame is the
// same to the bit, at the input size and upscaling (the shipped map), on a moving, jittered scene.
TEST_F(OwnResolveGpu, KdopsResolveGivenAsItsOwnGivesTheSameOutputsBitForBit) {
    for (const bool upscale : {false, true}) {
        SCOPED_TRACE(upscale ? "upscaling" : "at the input size");
        test::TempDir dir;
        ResolveOptions options;
        options.upscale = upscale;
        options.gamma = 1.25f;
        const std::uint32_t w = 40, h = 24, in_w = upscale ? w / 2 : w, in_h = upscale ? h / 2 : h;
        std::filesystem::path map = source_file("shader_templates/taa_resolve.bindings.json");
        if (!upscale) write_text(map = dir / "native.bindings.json", kNativeMap);
        auto own = load_own_resolve(kdops_resolve_as_own(dir.path(), options), map);
        ASSERT_TRUE(own) << own.error().message;

        std::vector<std::unique_ptr<RunnableVariant>> kdops;
        std::vector<BoundOwnResolve> owns;
        owns.reserve(2); // the roles are pointed to
        std::vector<const Variant*> shaders;
        std::vector<const BoundResolve*> roles;
        for (const VariantSpec& spec : {spec_of("dop16-grass", Mode::clip), spec_of("ycocg", Mode::varclip)}) {
            auto kdop = build_taa_shader(spec, options);
            ASSERT_TRUE(kdop) << kdop.error().message;
            auto bound = build_bound_resolve(*own, spec);
            ASSERT_TRUE(bound) << bound.error().message;
            kdops.push_back(std::move(*kdop));
            owns.push_back(std::move(*bound));
            shaders.insert(shaders.end(), {&kdops.back()->variant(), &owns.back().shader->variant()});
            roles.insert(roles.end(), {nullptr, &owns.back().roles});
        }
        auto resolve = TaaResolve::create(test::gpu(), shaders, in_w, in_h, w, h, options, {}, roles);
        ASSERT_TRUE(resolve) << resolve.error().message;
        const SceneFrames frames("grass", make_texture(TextureFamily::grass, in_w, in_h, 3), 8, true, false);
        for (std::size_t f = 0; f < frames.frame_count(); ++f) {
            auto frame = frames.frame(f);
            ASSERT_TRUE(frame);
            if (upscale) frame->jitter = halton_jitter(std::uint32_t(f), upscale_jitter_phases(2));
            ASSERT_TRUE((*resolve)->advance_all(*frame, frames.starts_history(f)));
            for (std::size_t s = 0; s < shaders.size(); s += 2)
                EXPECT_TRUE(same_bits((*resolve)->output(s), (*resolve)->output(s + 1)))
                    << shaders[s]->name << " against " << shaders[s + 1]->name << ", frame " << f;
        }
    }
}

// The engine example's TAAU resolves (GLSL and HLSL), each given with its shipped map and run
// through kdop's path beside kdop's upscaling resolve: float rounding apart (a history within
// rounding of a slab may land on either side, and then differs in the frames after), the three
// agree, as the example states for its own runner (EngineUpscaleGpu).
TEST_F(OwnResolveGpu, TheEngineExamplesUpscalersAgreeWithKdopsResolve) {
    constexpr std::uint32_t w = 32, h = 20, out_w = 64, out_h = 40;
    ResolveOptions options;
    options.upscale = true;
    const VariantSpec spec = spec_of("dop22", Mode::clip);
    auto kdop = build_taa_shader(spec, options);
    ASSERT_TRUE(kdop) << kdop.error().message;
    std::vector<BoundOwnResolve> engines;
    for (const char* name : {"upscale_compute.comp", "hlsl_upscale_compute.cs.hlsl"}) {
        const std::filesystem::path shader = source_file(std::string("examples/engine_resolve/") + name);
        std::filesystem::path map = shader;
        map.replace_filename(std::string(name).substr(0, std::string(name).find('.')) + ".bindings.json");
        auto own = load_own_resolve(shader, map);
        ASSERT_TRUE(own) << own.error().message;
        auto bound = build_bound_resolve(*own, spec);
        ASSERT_TRUE(bound) << bound.error().message;
        engines.push_back(std::move(*bound));
    }
    const Variant* shaders[] = {&(*kdop)->variant(), &engines[0].shader->variant(), &engines[1].shader->variant()};
    auto resolve = TaaResolve::create(test::gpu(), shaders, w, h, out_w, out_h, options, {},
                                      {nullptr, &engines[0].roles, &engines[1].roles});
    ASSERT_TRUE(resolve) << resolve.error().message;

    constexpr float kRounding = 1e-4f; // per pixel, the distance of two colors in [0, 1]
    const std::size_t pixels = std::size_t(out_w) * out_h;
    const auto pixels_apart = [&](const Image& a, const Image& b) {
        std::size_t apart = 0;
        for (std::size_t i = 0; i < pixels; ++i)
            if (glm::distance(glm::vec3(a.pixels[i]), glm::vec3(b.pixels[i])) > kRounding) ++apart;
        return apart;
    };
    const SceneFrames frames("grass", make_texture(TextureFamily::grass, w, h, 3), 8, true, false);
    std::size_t most_apart = 0;
    for (std::size_t f = 0; f < frames.frame_count(); ++f) {
        auto frame = frames.frame(f);
        ASSERT_TRUE(frame);
        frame->jitter = halton_jitter(std::uint32_t(f), upscale_jitter_phases(2));
        ASSERT_TRUE((*resolve)->advance_all(*frame, frames.starts_history(f)));
        for (std::size_t s : {1, 2}) {
            const std::size_t apart = pixels_apart((*resolve)->output(0), (*resolve)->output(s));
            EXPECT_LE(apart, pixels / 500) << shaders[s]->name << " against kdop's resolve, frame " << f;
            most_apart = std::max(most_apart, apart);
        }
        EXPECT_LE(pixels_apart((*resolve)->output(1), (*resolve)->output(2)), pixels / 500) << "frame " << f;
    }
    std::cout << "the engine's TAAU resolves through kdop taa --resolve's path, " << pixels
              << " pixels a frame: at most " << most_apart << " apart from kdop's by more than " << kRounding << "\n";
}

// tests/data/own_resolve/ycocg_resolve.comp, restated on the CPU for one frame after a start:
// clipped and blended in YCoCg with luminance weights, the history fetched at the motion (whole
// pixels here, so the linear sampler returns texels), off screen the current color.
glm::dvec3 to_ycocg(glm::dvec3 c) {
    return {0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b};
}
glm::dvec3 to_rgb(glm::dvec3 y) { return {y.x + y.y - y.z, y.x + y.z, y.x - y.y - y.z}; }

Image ycocg_resolve_on_cpu(const VariantSpec& spec, const Image& current, const Image& history, glm::ivec2 motion,
                           double weight, double gamma) {
    const std::vector<glm::dvec3> axes = unit_axes(spec.set);
    const std::vector<glm::ivec2> offsets = reference_offsets(spec.neighborhood);
    const int w = int(current.width), h = int(current.height);
    Image out;
    out.width = current.width, out.height = current.height;
    out.pixels.resize(current.pixels.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::vector<glm::dvec3> neighborhood;
            for (glm::ivec2 o : offsets) {
                const glm::ivec2 q = glm::clamp(glm::ivec2(x, y) + o, glm::ivec2(0), glm::ivec2(w - 1, h - 1));
                neighborhood.push_back(to_ycocg(glm::dvec3(current.pixels[std::size_t(q.y) * w + q.x])));
            }
            const glm::dvec3 c = to_ycocg(glm::dvec3(current.pixels[std::size_t(y) * w + x]));
            const glm::ivec2 previous = glm::ivec2(x, y) + motion;
            glm::dvec3 resolved = c;
            if (previous.x >= 0 && previous.y >= 0 && previous.x < w && previous.y < h) {
                const glm::dvec3 past = to_ycocg(glm::dvec3(history.pixels[std::size_t(previous.y) * w + previous.x]));
                const glm::dvec3 clipped = reference_clip(axes, neighborhood, c, past, spec.mode, gamma);
                const double w_current = weight / (1 + c.x), w_history = (1 - weight) / (1 + clipped.x);
                resolved = (w_current * c + w_history * clipped) / (w_current + w_history);
            }
            out.pixels[std::size_t(y) * w + x] = glm::vec4(glm::vec3(to_rgb(resolved)), 1.0f);
        }
    return out;
}

// Run with the output as the file declares it (rgba32f) and as rgba16f, the history format many
// engines keep: then every output is a half, and the CPU restatement agrees to a half's precision.
class OwnResolveFormatGpu : public test::ValidationChecked, public ::testing::WithParamInterface<const char*> {};

TEST_P(OwnResolveFormatGpu, AResolveInYCoCgWithALuminanceWeightMatchesItsCpuRestatement) {
    constexpr std::uint32_t w = 24, h = 16;
    const glm::ivec2 motion(2, -1);
    const bool half = std::string(GetParam()) == "rgba16f";
    ResolveOptions options;
    options.current_weight = 0.2f;
    options.gamma = 1.25f;
    test::TempDir dir;
    std::string text = read_input_file(source_file("tests/data/own_resolve/ycocg_resolve.comp")).value_or("");
    text.replace(text.find("rgba32f"), 7, GetParam());
    write_text(dir / "ycocg_resolve.comp", text);
    auto own =
        load_own_resolve(dir / "ycocg_resolve.comp", source_file("tests/data/own_resolve/ycocg_resolve.bindings.json"));
    ASSERT_TRUE(own) << own.error().message;
    const VariantSpec specs[] = {spec_of("dop16-grass", Mode::clip), spec_of("aabb", Mode::varclip),
                                 spec_of("dop22", Mode::clip, Neighborhood::n5)};
    std::vector<BoundOwnResolve> bound;
    bound.reserve(std::size(specs)); // the roles are pointed to
    std::vector<std::unique_ptr<RunnableVariant>> kdops;
    std::vector<const Variant*> shaders, kdop_shaders;
    std::vector<const BoundResolve*> roles;
    for (const VariantSpec& spec : specs) {
        auto built = build_bound_resolve(*own, spec);
        ASSERT_TRUE(built) << built.error().message;
        bound.push_back(std::move(*built));
        shaders.push_back(&bound.back().shader->variant());
        roles.push_back(&bound.back().roles);
        auto kdop = build_taa_shader(spec, options);
        ASSERT_TRUE(kdop) << kdop.error().message;
        kdops.push_back(std::move(*kdop));
        kdop_shaders.push_back(&kdops.back()->variant());
    }
    auto resolve = TaaResolve::create(test::gpu(), shaders, w, h, w, h, options, {}, roles);
    ASSERT_TRUE(resolve) << resolve.error().message;
    EXPECT_FALSE((*resolve)->takes_device_frames()) << "UV motion is converted on the host";
    auto kdop_resolve = TaaResolve::create(test::gpu(), kdop_shaders, w, h, options);
    ASSERT_TRUE(kdop_resolve) << kdop_resolve.error().message;

    LoadedFrame start{make_texture(TextureFamily::grass, w, h, 3), {}, {}, {}, {}};
    LoadedFrame next{
        make_texture(TextureFamily::grass, w, h, 5), std::vector<glm::vec2>(w * h, glm::vec2(motion)), {}, {}, {}};
    ASSERT_TRUE((*resolve)->advance_all(start, true));
    std::vector<Image> histories;
    for (std::size_t s = 0; s < shaders.size(); ++s) {
        histories.push_back((*resolve)->output(s));
        for (std::size_t i = 0; i < start.color.pixels.size(); ++i)
            ASSERT_LT(glm::distance(glm::vec3(histories[s].pixels[i]), glm::vec3(start.color.pixels[i])),
                      half ? 1e-3f : 1e-5f)
                << "a reset frame is its color, pixel " << i;
    }
    ASSERT_TRUE((*resolve)->advance_all(next, false));
    ASSERT_TRUE((*kdop_resolve)->advance_all(start, true));
    ASSERT_TRUE((*kdop_resolve)->advance_all(next, false));
    for (std::size_t s = 0; s < shaders.size(); ++s) {
        SCOPED_TRACE(shaders[s]->name);
        const Image expected =
            ycocg_resolve_on_cpu(specs[s], next.color, histories[s], motion, options.current_weight, options.gamma);
        const Image& got = (*resolve)->output(s);
        double largest = 0, from_kdops = 0;
        std::size_t not_halves = 0;
        for (std::size_t i = 0; i < expected.pixels.size(); ++i) {
            largest = std::max(largest, double(glm::distance(glm::vec3(got.pixels[i]), glm::vec3(expected.pixels[i]))));
            from_kdops += glm::distance(glm::vec3(got.pixels[i]), glm::vec3((*kdop_resolve)->output(s).pixels[i]));
            for (int c = 0; c < 3; ++c)
                not_halves += glm::unpackHalf1x16(glm::packHalf1x16(got.pixels[i][c])) != got.pixels[i][c];
        }
        // A half holds 11 significant bits: 2^-11 of a value below 1, and the history was rounded too.
        EXPECT_LT(largest, half ? 2e-3 : 2e-4) << "against the CPU restatement";
        if (half) {
            EXPECT_EQ(not_halves, 0u) << "the output was written as rgba16f";
        } else {
            EXPECT_GT(not_halves, 0u) << "the output was written as rgba32f";
        }
        // It changes what a viewer sees: kdop's resolve, same variant and weight, differs.
        EXPECT_GT(from_kdops / double(expected.pixels.size()), 1e-3) << "against kdop's resolve";
        std::cout << shaders[s]->name << " (" << GetParam() << "): largest distance from the CPU restatement "
                  << largest << ", mean from kdop's resolve " << from_kdops / double(expected.pixels.size()) << "\n";
    }
}

INSTANTIATE_TEST_SUITE_P(Output, OwnResolveFormatGpu, ::testing::Values("rgba32f", "rgba16f"));

// The YCoCg resolve with its values in a uniform block (a cbuffer) instead of push constants,
// bound by "<block>.<member>" under the map's "uniforms": the same outputs to the bit. What does
// not fit is refused, naming the member.
TEST_F(OwnResolveGpu, UniformBlockMembersAreFilledAsPushConstantsAre) {
    constexpr std::uint32_t w = 24, h = 16;
    test::TempDir dir;
    std::string text = read_input_file(source_file("tests/data/own_resolve/ycocg_resolve.comp")).value_or("");
    const std::string push = "layout(push_constant) uniform Constants";
    ASSERT_NE(text.find(push), std::string::npos);
    text.replace(text.find(push), push.size(), "layout(set = 0, binding = 5) uniform Constants");
    write_text(dir / "uniform_resolve.comp", text);
    std::string map = read_input_file(source_file("tests/data/own_resolve/ycocg_resolve.bindings.json")).value_or("");
    const std::string values = R"("push_constants": {
    "reset": "reset",
    "blend": "current_weight",
    "variance_gamma": "gamma"
  })";
    ASSERT_NE(map.find(values), std::string::npos) << map;
    const std::string uniforms = R"("uniforms": {"constants.reset": "reset", "constants.blend": "current_weight",
                 "constants.variance_gamma": "gamma"})";
    write_text(dir / "uniform.json", std::string(map).replace(map.find(values), values.size(), uniforms));

    auto by_push = load_own_resolve(source_file("tests/data/own_resolve/ycocg_resolve.comp"),
                                    source_file("tests/data/own_resolve/ycocg_resolve.bindings.json"));
    auto by_uniform = load_own_resolve(dir / "uniform_resolve.comp", dir / "uniform.json");
    ASSERT_TRUE(by_push) << by_push.error().message;
    ASSERT_TRUE(by_uniform) << by_uniform.error().message;
    const VariantSpec spec = spec_of("dop16-grass", Mode::varclip);
    std::vector<BoundOwnResolve> bound;
    bound.reserve(2);
    for (const OwnResolve* resolve : {&*by_push, &*by_uniform}) {
        auto built = build_bound_resolve(*resolve, spec);
        ASSERT_TRUE(built) << built.error().message;
        bound.push_back(std::move(*built));
    }
    EXPECT_EQ(bound[1].roles.uniforms.size(), 3u);
    EXPECT_TRUE(bound[1].roles.values.empty());
    ResolveOptions options;
    options.current_weight = 0.2f;
    options.gamma = 1.25f;
    const Variant* shaders[] = {&bound[0].shader->variant(), &bound[1].shader->variant()};
    auto resolve =
        TaaResolve::create(test::gpu(), shaders, w, h, w, h, options, {}, {&bound[0].roles, &bound[1].roles});
    ASSERT_TRUE(resolve) << resolve.error().message;
    const LoadedFrame frames[] = {
        {make_texture(TextureFamily::grass, w, h, 3), {}, {}, {}, {}},
        {make_texture(TextureFamily::grass, w, h, 5), std::vector<glm::vec2>(w * h, glm::vec2(2, -1)), {}, {}, {}},
        {make_texture(TextureFamily::grass, w, h, 7), std::vector<glm::vec2>(w * h, glm::vec2(-1, 1)), {}, {}, {}}};
    for (std::uint32_t f = 0; f < 3; ++f) {
        ASSERT_TRUE((*resolve)->advance_all(frames[f], f == 0, true, f));
        EXPECT_TRUE(same_bits((*resolve)->output(0), (*resolve)->output(1))) << "frame " << f;
    }

    // A member left without a role, a member the block lacks, a role given twice: refused.
    const struct {
        std::string from, to, says;
    } wrong[] = {
        {"\"constants.variance_gamma\": \"gamma\"", "\"constants.variance_gamma2\": \"gamma\"",
         "uniforms.constants.variance_gamma2: the shader has no uniform block member"},
        {", \"constants.blend\": \"current_weight\"", "",
         "its uniform block member \"constants.blend\" has no role in the map's \"uniforms\""},
        {"\"resources\": {", "\"push_constants\": {\"unused\": \"reset\"}, \"resources\": {",
         "uniforms.constants.reset: the role reset is also given to push_constants.unused"},
    };
    const std::string good = read_input_file(dir / "uniform.json").value_or("");
    for (const auto& c : wrong) {
        SCOPED_TRACE(c.says);
        std::string text_map = good;
        ASSERT_NE(text_map.find(c.from), std::string::npos) << text_map;
        write_text(dir / "wrong.json", text_map.replace(text_map.find(c.from), c.from.size(), c.to));
        auto loaded = load_own_resolve(dir / "uniform_resolve.comp", dir / "wrong.json");
        const std::string message = !loaded ? loaded.error().message : [&] {
            auto built = build_bound_resolve(*loaded, spec);
            return built ? std::string("bound") : built.error().message;
        }();
        EXPECT_NE(message.find(c.says), std::string::npos) << message;
    }
}

// kdop/resolve_runner.h, the helper an engine compiles into its tools, runs the YCoCg resolve as
// kdop's own path runs it: the same outputs to the bit over a start and a moving frame, the
// history kept on the device. What it cannot bind or fill is refused, naming it.
TEST_F(OwnResolveGpu, TheInstalledRunHelperResolvesAsKdopsPathDoes) {
    constexpr std::uint32_t w = 24, h = 16;
    auto own = load_own_resolve(source_file("tests/data/own_resolve/ycocg_resolve.comp"),
                                source_file("tests/data/own_resolve/ycocg_resolve.bindings.json"));
    ASSERT_TRUE(own) << own.error().message;
    auto bound = build_bound_resolve(*own, spec_of("dop22", Mode::clip));
    ASSERT_TRUE(bound) << bound.error().message;
    const Variant& shader = bound->shader->variant();
    ResolveOptions options;
    options.current_weight = 0.2f;
    const Variant* shaders[] = {&shader};
    auto kdops = TaaResolve::create(test::gpu(), shaders, w, h, w, h, options, {}, {&bound->roles});
    ASSERT_TRUE(kdops) << kdops.error().message;

    const kdop::RunnerDevice device{test::gpu().instance(), test::gpu().physical_device(), test::gpu().device(),
                                    test::gpu().queue(),    test::gpu().queue_family(),    vkGetInstanceProcAddr};
    ResolveRunner::Layout layout;
    layout.inputs = {{"scene_color", w, h}, {"scene_velocity", w, h}, {"accumulated", w, h}};
    layout.output = "resolved";
    layout.width = w, layout.height = h;
    layout.history = "accumulated";
    std::string error;
    auto runner = ResolveRunner::create(device, shader, layout, error);
    ASSERT_TRUE(runner) << error;

    const glm::vec2 motion_pixels(2, -1), motion_uv = motion_pixels / glm::vec2(w, h);
    const std::vector<float> zero_motion(std::size_t(w) * h * 4, 0.0f);
    std::vector<float> uv_motion(std::size_t(w) * h * 4, 0.0f);
    for (std::size_t i = 0; i < std::size_t(w) * h; ++i)
        uv_motion[4 * i] = motion_uv.x, uv_motion[4 * i + 1] = motion_uv.y;
    const LoadedFrame frames[] = {
        {make_texture(TextureFamily::grass, w, h, 3), {}, {}, {}, {}},
        {make_texture(TextureFamily::grass, w, h, 5), std::vector<glm::vec2>(w * h, motion_pixels), {}, {}, {}}};
    std::vector<float> out;
    EXPECT_NE(runner->resolve(&out).find("push constant 'reset' was never set"), std::string::npos);
    for (std::uint32_t f = 0; f < 2; ++f) {
        ASSERT_TRUE((*kdops)->advance_all(frames[f], f == 0));
        const std::vector<float> color(&frames[f].color.pixels[0].x, &frames[f].color.pixels[0].x + 4 * w * h);
        const std::uint32_t reset = f == 0;
        const float blend = f == 0 ? 1.0f : options.current_weight, gamma = options.gamma;
        for (const std::string& e :
             {runner->set_input("scene_color", color.data(), color.size()),
              runner->set_input("scene_velocity", (f == 0 ? zero_motion : uv_motion).data(), uv_motion.size()),
              runner->set_push_constant("reset", &reset, 4), runner->set_push_constant("blend", &blend, 4),
              runner->set_push_constant("variance_gamma", &gamma, 4), runner->resolve(&out)})
            ASSERT_EQ(e, "");
        const Image& expected = (*kdops)->output(0);
        ASSERT_EQ(out.size(), 4 * expected.pixels.size());
        EXPECT_EQ(std::memcmp(out.data(), expected.pixels.data(), out.size() * sizeof(float)), 0) << "frame " << f;
    }

    EXPECT_NE(runner->set_input("scene_color", out.data(), 8).find("takes 24x16 RGBA texels, not 8 floats"),
              std::string::npos);
    EXPECT_NE(runner->set_push_constant("blend", &w, 8).find("is 4 bytes, not 8"), std::string::npos);
    EXPECT_NE(runner->set_input("depth", out.data(), out.size()).find("has no input 'depth'"), std::string::npos);
    layout.inputs.pop_back(); // the history's texture left out
    EXPECT_FALSE(ResolveRunner::create(device, shader, layout, error));
    EXPECT_NE(error.find("its binding 'accumulated' is not in the layout's inputs or output"), std::string::npos)
        << error;
}

// kdop taa over a 3-D scene upscaled 2x, with kdop's resolve and with the same given as
// --resolve with the shipped map: the same files but the timings, and the resolve named.
TEST(CliOwnResolve, KdopsResolveGivenAsItsOwnGivesTheSameFiles) {
    test::TempDir dir;
    ResolveOptions options;
    options.upscale = true;
    const std::filesystem::path shader = kdops_resolve_as_own(dir.path(), options);
    const std::string common = test::kdop_binary() +
                               " taa --scenes grass3d --upscale 2 --size 64x36 --warmup 4 --frames 4 --sets aabb "
                               "dop16-grass --modes clip varclip --viewer-frames 0 --no-charts --out ";
    auto kdops = test::run(common + (dir / "kdop").string());
    ASSERT_EQ(kdops.exit_code, 0) << kdops.err;
    auto own = test::run(common + (dir / "own").string() + " --resolve " + shader.string() + " --resolve-bindings " +
                         source_file("shader_templates/taa_resolve.bindings.json").string());
    ASSERT_EQ(own.exit_code, 0) << own.err;
    for (const char* table : {"taa.csv", "taa_frames.csv"}) {
        auto a = test::csv_rows(read_input_file(dir / "kdop" / table).value_or(""));
        // kdop's run has the spatial-only row too: its filter, which a renderer's resolve does not have.
        std::erase_if(a, [](auto& row) { return row["variant"].starts_with("spatial-"); });
        auto b = test::csv_rows(read_input_file(dir / "own" / table).value_or(""));
        ASSERT_EQ(a.size(), b.size()) << table;
        ASSERT_FALSE(a.empty()) << table;
        for (std::size_t r = 0; r < a.size(); ++r)
            for (const auto& [column, value] : a[r])
                if (!column.starts_with("ms")) {
                    EXPECT_EQ(b[r][column], value) << table << " row " << r << " " << column;
                }
    }
    const std::string label = "taa_resolve.comp (fnv1a64 ";
    EXPECT_NE(read_input_file(dir / "own" / "report.md").value_or("").find("- resolve: `" + label), std::string::npos);
    const auto json = nlohmann::json::parse(read_input_file(dir / "own" / "taa.json").value_or("{}"));
    EXPECT_TRUE(json.dump().find(label) != std::string::npos) << "taa.json names the resolve";
    EXPECT_EQ(read_input_file(dir / "kdop" / "report.md").value_or("").find("- resolve:"), std::string::npos);
}

// kdop choose judges its candidates through the resolve given: kdop's own given as --resolve
// gives every held-out figure of a run without it, and the outputs name the resolve. The manifest
// records no settings of kdop's resolve, which the figures were not measured with.
TEST(CliOwnResolve, ChooseJudgesTheCandidatesThroughTheResolveGiven) {
    test::TempDir dir;
    auto s = test::run(test::kdop_binary() + " scene --scenes grass asphalt --size 40x24 --frames 10 --out " +
                       (dir / "scenes").string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    write_text(dir / "native.bindings.json", kNativeMap);
    const std::filesystem::path shader = kdops_resolve_as_own(dir.path(), {});
    const std::string choose = test::kdop_binary() + " choose --fit " + (dir / "scenes" / "grass-ghosting").string() +
                               " --validate " + (dir / "scenes" / "asphalt-ghosting").string() +
                               " --fit-axes 4 --sets aabb --warmup 3 --sample 1500 --timing-rounds 2 --no-charts ";
    auto kdops = test::run(choose + "--out " + (dir / "kdop").string());
    ASSERT_EQ(kdops.exit_code, 0) << kdops.err;
    auto own = test::run(choose + "--out " + (dir / "own").string() + " --resolve " + shader.string() +
                         " --resolve-bindings " + (dir / "native.bindings.json").string());
    ASSERT_EQ(own.exit_code, 0) << own.err;
    auto a = test::csv_rows(read_input_file(dir / "kdop" / "candidates.csv").value_or(""));
    auto b = test::csv_rows(read_input_file(dir / "own" / "candidates.csv").value_or(""));
    ASSERT_EQ(a.size(), b.size());
    ASSERT_FALSE(a.empty());
    for (std::size_t r = 0; r < a.size(); ++r) {
        EXPECT_EQ(a[r]["variant"], b[r]["variant"]);
        EXPECT_EQ(a[r]["validation_ghosting"], b[r]["validation_ghosting"]) << a[r]["variant"];
    }
    const std::string manifest = read_input_file(dir / "own" / "kdop.manifest").value_or("");
    EXPECT_NE(manifest.find("# Measured through your own resolve, taa_resolve.comp (fnv1a64 "), std::string::npos)
        << manifest;
    EXPECT_EQ(manifest.find("current-weight:"), std::string::npos) << manifest;
    EXPECT_NE(read_input_file(dir / "kdop" / "kdop.manifest").value_or("").find("current-weight:"), std::string::npos);
    const std::string report = read_input_file(dir / "own" / "choice.md").value_or("");
    EXPECT_NE(report.find("| resolve | `taa_resolve.comp (fnv1a64 "), std::string::npos) << report;
    EXPECT_NE(report.find("- resolve: `taa_resolve.comp"), std::string::npos);
}

// What kdop cannot measure is refused before any frame, naming what is wrong, with nothing written.
TEST(CliOwnResolve, RefusalsNameWhatIsWrongAndWriteNothing) {
    test::TempDir dir;
    const std::string shader_text =
        read_input_file(source_file("tests/data/own_resolve/ycocg_resolve.comp")).value_or("");
    const std::string map_text =
        read_input_file(source_file("tests/data/own_resolve/ycocg_resolve.bindings.json")).value_or("");
    ASSERT_FALSE(shader_text.empty());
    const auto with = [](std::string text, const std::string& from, const std::string& to) {
        const std::size_t at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return at == std::string::npos ? text : text.replace(at, from.size(), to);
    };
    const auto file = [&](const std::string& name, const std::string& text) {
        write_text(dir / name, text);
        return (dir / name).string();
    };
    const std::string good = file("good.comp", shader_text), map = file("good.json", map_text);
    const struct {
        std::string args;
        int exit_code;
        std::string says;
    } cases[] = {
        {"--resolve " + good, 2, "--resolve: needs --resolve-bindings"},
        {"--resolve-bindings " + map, 2, "--resolve-bindings: is the map of a --resolve"},
        {"--resolve " + good + " --resolve-bindings " + map + " --history-filter catmull-rom", 2,
         "--history-filter: is an option of kdop's own resolve"},
        {"--resolve " + good + " --resolve-bindings " + map + " --hlsl-entry CSMain", 2, "--hlsl-entry: names"},
        {"--resolve " +
             file("no_include.comp",
                  with(shader_text, "#include \"kdop_variant.glsl\"",
                       "#define KDOP_NEIGHBORS 9\nvec3 kdop_rectify(vec3 c, vec3 h, float g, vec3 n[9]) "
                       "{ return h; }")) +
             " --resolve-bindings " + map,
         1, "does not #include \"kdop_variant.glsl\""},
        {"--resolve " +
             file("broken.comp", with(shader_text, "    const vec2 uv",
                                      "    vec2 uv = undefined_name;\n"
                                      "    const vec2 uv2")) +
             " --resolve-bindings " + map,
         1, "broken.comp:"},
        {"--resolve " + good + " --resolve-bindings " +
             file("extra.json",
                  with(map_text, "\"resolved\": \"output\"", "\"resolved\": \"output\", \"gone\": \"depth\"")),
         1, "the shader has no resource \"gone\""},
        {"--resolve " + good + " --resolve-bindings " +
             file("unbound.json", with(map_text, "\"linear_clamp\": \"sampler\",", "")),
         1, "its resource \"linear_clamp\" (set 0, binding 3) has no role"},
        {"--resolve " + good + " --resolve-bindings " +
             file("mistyped.json", with(map_text, "\"resolved\": \"output\"", "\"resolved\": \"depth\"")),
         1, "resources.resolved: the role depth takes a sampled image"},
        {"--resolve " + file("ldr.comp", with(shader_text, "rgba32f", "rgba8")) + " --resolve-bindings " + map, 1,
         "resources.resolved: the role output takes a storage image of rgba32f or rgba16f"},
        {"--resolve " + good + " --resolve-bindings " + (dir / "missing.json").string(), 1, "missing.json"},
    };
    for (const auto& c : cases) {
        const std::filesystem::path out = dir / "out";
        auto r = test::run(test::kdop_binary() + " taa --scenes grass --size 32x18 --warmup 2 --frames 2 --sets aabb " +
                           "--modes clip --out " + out.string() + " " + c.args);
        EXPECT_EQ(r.exit_code, c.exit_code) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
        EXPECT_FALSE(std::filesystem::exists(out) && !std::filesystem::is_empty(out)) << c.args;
    }
}

} // namespace
} // namespace kdop
