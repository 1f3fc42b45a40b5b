// The upscaling resolve (shader_templates/taa_resolve.comp.in with KDOP_UPSCALE): every output
// pixel as a CPU restatement of the resolve computes it, for both filters; a still jittered 3-D
// scene converging to its supersampled reference, below the spatial-only upscale of the same
// input; and kdop taa --upscale's refusals.
#include "flip/flip.h"
#include "generator/variant_spec.h"
#include "images/image_io.h"
#include "images/texture_cases.h"
#include "reference/cpu_clip.h"
#include "scenes/sprite_scene.h"
#include "scenes/testbed_scene.h"
#include "sequence/jitter.h"
#include "temporal/taa_resolve.h"
#include "temporal/taa_shader.h"
#include "testbed/scene3d.h"
#include "tests/gpu_support.h"
#include "tests/test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

namespace kdop {
namespace {

// The upscaling resolve restated on the CPU, in double, from the shader's comment: the nearest
// input sample, its neighborhood, the filtered current color, the scaled motion and the weight.
struct CpuUpscale {
    ResolveOptions o;
    std::vector<glm::dvec3> axes;
    Mode mode = Mode::clip;

    double filter(glm::dvec2 d) const {
        if (o.upscale_filter == UpscaleFilter::gaussian) return std::exp(-2 * glm::dot(d, d));
        const double x = glm::length(d);
        if (x < 1e-5) return 1;
        if (x >= 2) return 0;
        const double pi_x = std::numbers::pi * x;
        return 2 * std::sin(pi_x) * std::sin(0.5 * pi_x) / (pi_x * pi_x);
    }
    static glm::dvec3 at(const Image& image, glm::ivec2 q) { return glm::dvec3(glm::vec3(image.clamped(q.x, q.y))); }
    static glm::dvec3 bilinear(const Image& h, glm::dvec2 x) {
        const glm::dvec2 t = x - 0.5, f = t - glm::floor(t);
        const glm::ivec2 i(glm::floor(t));
        return glm::mix(glm::mix(at(h, i), at(h, i + glm::ivec2(1, 0)), f.x),
                        glm::mix(at(h, i + glm::ivec2(0, 1)), at(h, i + glm::ivec2(1, 1)), f.x), f.y);
    }

    Image frame(const LoadedFrame& f, bool starts_history, const Image& history, std::uint32_t width,
                std::uint32_t height) const {
        const Image& c = f.color;
        const glm::ivec2 in_last(int(c.width) - 1, int(c.height) - 1);
        const glm::dvec2 scale(double(c.width) / width, double(c.height) / height), jitter(f.jitter);
        const std::vector<glm::ivec2> offsets = reference_offsets(Neighborhood::n9);
        Image out(width, height);
        for (std::uint32_t y = 0; y < height; ++y)
            for (std::uint32_t x = 0; x < width; ++x) {
                const glm::dvec2 center = (glm::dvec2(x, y) + 0.5) * scale;
                const glm::ivec2 nearest = glm::clamp(glm::ivec2(glm::floor(center - jitter)), glm::ivec2(0), in_last);
                std::vector<glm::dvec3> neighborhood;
                for (glm::ivec2 d : offsets) neighborhood.push_back(at(c, nearest + d));
                // UE4's sample distance: a neighbor whose sample lies that far from the center
                // stands in as the center sample.
                const double limit = o.sample_distance.at(float(width) / float(c.width));
                for (std::size_t i = 0; i < neighborhood.size(); ++i) {
                    const glm::dvec2 d = glm::dvec2(offsets[i] + nearest) + 0.5 + jitter - center;
                    if (glm::dot(d, d) >= limit * limit) neighborhood[i] = neighborhood[4];
                }
                glm::dvec3 sum(0), low(1e30), high(-1e30);
                double weights = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const glm::ivec2 q = glm::clamp(nearest + glm::ivec2(dx, dy), glm::ivec2(0), in_last);
                        const double w = filter(glm::dvec2(q) + 0.5 + jitter - center);
                        sum += w * at(c, q), weights += w;
                        low = glm::min(low, at(c, q)), high = glm::max(high, at(c, q));
                    }
                const glm::dvec3 current = glm::clamp(sum / weights, low, high);
                if (o.no_history) {
                    out.at(x, y) = glm::vec4(glm::vec3(current), 1);
                    continue;
                }
                const glm::dvec2 motion =
                    glm::dvec2(f.motion.empty() ? glm::vec2(0) : f.motion[nearest.y * c.width + nearest.x]) / scale;
                const glm::dvec2 previous = glm::dvec2(x, y) + 0.5 + motion;
                if (starts_history || previous.x < 0 || previous.y < 0 || previous.x > width || previous.y > height) {
                    out.at(x, y) = glm::vec4(glm::vec3(current), 1);
                    continue;
                }
                const glm::dvec2 offset = (glm::dvec2(nearest) + 0.5 + jitter - center) / scale;
                const double weight = o.current_weight * std::exp(-2 * glm::dot(offset, offset));
                // The clip's ray starts at the nearest sample, the neighborhood's center.
                const glm::dvec3 r =
                    reference_clip(axes, neighborhood, neighborhood[4], bilinear(history, previous), mode,
                                   o.gamma * box_scale_at(o.box_scale, float(width) / float(c.width)));
                out.at(x, y) = glm::vec4(glm::vec3(r + weight * (current - r)), 1);
            }
        return out;
    }
};

std::size_t pixels_apart(const Image& a, const Image& b, float tolerance) {
    std::size_t off = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        if (glm::distance(glm::vec3(a.pixels[i]), glm::vec3(b.pixels[i])) > tolerance) ++off;
    return off;
}

std::unique_ptr<TaaResolve> upscaling_resolve(const RunnableVariant& shader, std::uint32_t input_width,
                                              std::uint32_t input_height, std::uint32_t width, std::uint32_t height,
                                              const ResolveOptions& options) {
    const Variant* shaders[] = {&shader.variant()};
    auto resolve = TaaResolve::create(test::gpu(), shaders, input_width, input_height, width, height, options);
    EXPECT_TRUE(resolve) << resolve.error().message;
    return resolve ? std::move(*resolve) : nullptr;
}

// Resolves `frames` (32x20, jittered over 2x's Halton phases) to 64x40 with `shader` and checks
// every frame against `cpu`'s restatement; returns the last output. `label` names the case.
Image expect_restated(const RunnableVariant& shader, const SceneFrames& frames, const CpuUpscale& cpu,
                      const std::string& label) {
    constexpr std::uint32_t w = 32, h = 20, out_w = 64, out_h = 40;
    auto resolve = upscaling_resolve(shader, w, h, out_w, out_h, cpu.o);
    if (!resolve) return {};
    Image history;
    for (std::size_t f = 0; f < frames.frame_count(); ++f) {
        auto frame = frames.frame(f);
        EXPECT_TRUE(frame);
        if (!frame) return {};
        frame->jitter = halton_jitter(std::uint32_t(f), upscale_jitter_phases(2));
        auto gpu = resolve->advance(*frame, frames.starts_history(f));
        EXPECT_TRUE(gpu) << gpu.error().message;
        if (!gpu) return {};
        EXPECT_EQ((*gpu)->width, out_w);
        const Image expected = cpu.frame(*frame, frames.starts_history(f), history, out_w, out_h);
        // float32 against double; a history within rounding of a slab may land on either side.
        EXPECT_LE(pixels_apart(expected, **gpu, 2e-4f), expected.pixels.size() / 500) << label << ", frame " << f;
        history = **gpu;
    }
    return history;
}

using UpscaleGpu = test::ValidationChecked;

// A moving 2-D scene drawn at 32x20, upscaled 2x with a Halton jitter: every output as the CPU
// restatement computes it, with the Lanczos-2 and the Gaussian filter.
TEST_F(UpscaleGpu, EachFilterMatchesTheCpuRestatement) {
    const SceneFrames frames("grass", make_texture(TextureFamily::grass, 32, 20, 3), 24, true, false);
    EXPECT_EQ(upscale_jitter_phases(2), 32u);
    for (const UpscaleFilter filter : {UpscaleFilter::lanczos2, UpscaleFilter::gaussian}) {
        ResolveOptions options;
        options.upscale = true;
        options.upscale_filter = filter;
        const VariantSpec spec{*resolve_axis_set("dop22"), Mode::clip, Neighborhood::n9};
        auto shader = build_taa_shader(spec, options);
        ASSERT_TRUE(shader) << shader.error().message;
        expect_restated(**shader, frames, CpuUpscale{options, unit_axes(spec.set), Mode::clip}, to_string(filter));
    }
}

// The choices engines make differently, on the same scene at 2x: UE4's sample distance (a fixed
// 1.2 input pixels here, and UE4's own, 1.3 at 2x), FSR 2.0's box scale (the variance clip's
// gamma times 1.5 at 2x) and the spatial-only upscale. Each matches the CPU restatement, and each
// changes the outputs (so none is a define the shader ignores).
TEST_F(UpscaleGpu, EachEngineChoiceMatchesTheCpuRestatement) {
    const SceneFrames frames("grass", make_texture(TextureFamily::grass, 32, 20, 3), 16, true, false);
    const VariantSpec spec{*resolve_axis_set("dop22"), Mode::varclip, Neighborhood::n9};
    struct Choice {
        const char* name;
        ResolveOptions options;
    };
    std::vector<Choice> choices(5);
    for (Choice& c : choices) c.options.upscale = true;
    choices[0].name = "the defaults";
    choices[1].name = "samples within 1.2 input pixels";
    choices[1].options.sample_distance = {SampleDistance::Kind::fixed, 1.2f};
    choices[2].name = "UE4's sample distance";
    choices[2].options.sample_distance = {SampleDistance::Kind::ue4, 0};
    choices[3].name = "FSR 2.0's box scale";
    choices[3].options.box_scale = BoxScale::fsr2;
    choices[4].name = "the spatial-only upscale";
    choices[4].options.no_history = true;
    EXPECT_FLOAT_EQ(choices[2].options.sample_distance.at(2), 1.3f);
    EXPECT_FLOAT_EQ(box_scale_at(BoxScale::fsr2, 2), 1.5f);
    std::vector<Image> last(choices.size());
    for (std::size_t c = 0; c < choices.size(); ++c) {
        const ResolveOptions& options = choices[c].options;
        auto shader = options.no_history ? build_spatial_upscale_shader(options) : build_taa_shader(spec, options);
        ASSERT_TRUE(shader) << shader.error().message;
        const Image history =
            expect_restated(**shader, frames, CpuUpscale{options, unit_axes(spec.set), Mode::varclip}, choices[c].name);
        last[c] = history;
        if (c > 0) {
            EXPECT_GT(pixels_apart(last[0], last[c], 1e-3f), last[0].pixels.size() / 50)
                << choices[c].name << " leaves the last output as the defaults'";
        }
    }
}

// The still grass3d scene drawn at 48x27 and upscaled to 96x54: its output's FLIP against the 16-
// sample reference falls over the frames, and ends at most 0.6 of the spatial-only (measured: 0.40) upscale's (the
// same filter on the same input without a history: current weight 1).
TEST_F(UpscaleGpu, AStillJitteredSceneConvergesBelowTheSpatialUpscale) {
    constexpr std::uint32_t width = 96, height = 54;
    auto scene = TestbedScene::create(test::gpu(), grass3d_scene(1), width, height, false, 16, 2);
    ASSERT_TRUE(scene) << scene.error().message;
    const auto frames = (*scene)->frames("still", 40, false, true);
    ASSERT_EQ(frames->input_width(), 48u);
    ASSERT_EQ(frames->width(), width);
    ResolveOptions options;
    options.upscale = true;
    const VariantSpec spec{*resolve_axis_set("aabb"), Mode::clip, Neighborhood::n9};
    // The spatial-only upscale is the row kdop taa puts beside the variants.
    auto shader = build_taa_shader(spec, options);
    auto spatial = build_spatial_upscale_shader(options);
    ASSERT_TRUE(shader && spatial);
    auto with_history = upscaling_resolve(**shader, 48, 27, width, height, options);
    auto without = upscaling_resolve(**spatial, 48, 27, width, height, options);
    ASSERT_TRUE(with_history && without);
    const LdrFlip flip(67);
    std::vector<double> temporal_flip, spatial_flip;
    for (std::size_t f = 0; f < frames->frame_count(); ++f) {
        auto frame = frames->frame(f);
        ASSERT_TRUE(frame) << frame.error().message;
        ASSERT_TRUE(frame->reference);
        auto a = with_history->advance(*frame, frames->starts_history(f));
        ASSERT_TRUE(a) << a.error().message;
        auto a_flip = flip.mean(*frame->reference, **a);
        auto b = without->advance(*frame, frames->starts_history(f));
        ASSERT_TRUE(b) << b.error().message;
        auto b_flip = flip.mean(*frame->reference, **b);
        ASSERT_TRUE(a_flip && b_flip);
        temporal_flip.push_back(*a_flip), spatial_flip.push_back(*b_flip);
    }
    std::cout << fmt::format("LDR-FLIP against the reference, frames 2 and 39: temporal {:.4f} -> {:.4f}, spatial-only "
                             "{:.4f} -> {:.4f}\n",
                             temporal_flip[2], temporal_flip.back(), spatial_flip[2], spatial_flip.back());
    EXPECT_LT(temporal_flip.back(), temporal_flip[2]) << "the output converges";
    EXPECT_LE(temporal_flip.back(), 0.6 * spatial_flip.back())
        << "temporal " << temporal_flip.back() << ", spatial " << spatial_flip.back();
}

// A smooth pattern sliding 1.5 output pixels a frame, drawn at 32x20 with a Halton jitter and
// upscaled to 64x40: with the exact motion (0.75 input pixels) the output follows the pattern, with
// at most half the error it keeps with no motion or with the motion in output pixels by mistake
// (twice as far), where the history lags or leads and the clip must cut it.
TEST_F(UpscaleGpu, AMovingPatternIsTrackedByItsMotion) {
    constexpr std::uint32_t w = 32, h = 20, out_w = 64, out_h = 40;
    constexpr float speed = 1.5f; // output pixels a frame, to the right
    auto pattern = [](float x, float y) {
        const float v = 0.5f + 0.35f * std::sin(0.45f * x) * std::cos(0.3f * y);
        return glm::vec4(v, 0.8f * v, 1.0f - v, 1.0f);
    };
    const std::uint32_t phases = upscale_jitter_phases(2);
    auto frame = [&](std::size_t f, float motion) {
        LoadedFrame out;
        out.jitter = halton_jitter(std::uint32_t(f), phases);
        out.color = Image(w, h);
        for (std::uint32_t y = 0; y < h; ++y)
            for (std::uint32_t x = 0; x < w; ++x) {
                const glm::vec2 at = (glm::vec2(x, y) + 0.5f + out.jitter) * 2.0f; // in output pixels
                out.color.at(x, y) = pattern(at.x - speed * float(f), at.y);
            }
        // Where each sample's surface was a frame ago, in input pixels.
        if (f > 0) out.motion.assign(std::size_t(w) * h, glm::vec2(motion, 0.0f));
        return out;
    };
    ResolveOptions options;
    options.upscale = true;
    const VariantSpec spec{*resolve_axis_set("dop22"), Mode::clip, Neighborhood::n9};
    auto shader = build_taa_shader(spec, options);
    ASSERT_TRUE(shader) << shader.error().message;
    // The mean error of the last frame with the exact motion, none, and twice the exact.
    const float motions[] = {-speed / 2, 0.0f, -speed};
    double error[3] = {0, 0, 0};
    for (int m = 0; m < 3; ++m) {
        auto resolve = upscaling_resolve(**shader, w, h, out_w, out_h, options);
        ASSERT_TRUE(resolve);
        const Image* output = nullptr;
        constexpr std::size_t frames = 30;
        for (std::size_t f = 0; f < frames; ++f) {
            auto out = resolve->advance(frame(f, motions[m]), f == 0);
            ASSERT_TRUE(out) << out.error().message;
            output = *out;
        }
        // Away from the left edge, where the pattern enters without a history.
        double sum = 0;
        std::size_t count = 0;
        for (std::uint32_t y = 0; y < out_h; ++y)
            for (std::uint32_t x = 8; x < out_w; ++x, ++count) {
                const glm::vec4 truth = pattern(float(x) + 0.5f - speed * float(frames - 1), float(y) + 0.5f);
                sum += glm::length(glm::vec3(output->at(x, y) - truth));
            }
        error[m] = sum / double(count);
    }
    std::cout << fmt::format("mean error of the last frame: {:.4f} with the motion, {:.4f} without, {:.4f} with "
                             "twice the motion\n",
                             error[0], error[1], error[2]);
    EXPECT_LT(error[0], 0.5 * error[1]);
    EXPECT_LT(error[0], 0.5 * error[2]);
}

// kdop taa --upscale on a 2-D scene, alone or beside a 3-D one, or with a background: exit 2 before
// any work, naming the option, nothing written.
TEST(CliUpscale, TwoDimensionalScenesAreRefused) {
    test::TempDir dir;
    const std::string background = (dir / "background.png").string();
    ASSERT_TRUE(write_image(background, make_texture(TextureFamily::grass, 16, 16, 1)));
    const struct {
        std::string args;
        const char* says;
    } cases[] = {{"--scenes grass", "--upscale: only the 3-D scenes"},
                 {"--scenes grass3d grass", "--scenes: grass is a 2-D scene, drawn at one size"},
                 {"--scenes grass3d --background " + background, "--background: a 2-D scene"}};
    for (const auto& c : cases) {
        const std::filesystem::path out = dir / "out";
        auto r = test::run(test::kdop_binary() + " taa --upscale 2 --sets aabb --modes clip " + c.args + " --out " +
                           out.string());
        EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
    }
}

} // namespace
} // namespace kdop
