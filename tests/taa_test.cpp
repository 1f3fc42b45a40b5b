// The temporal evaluation (temporal/, `kdop taa`): the scene's animation, jitter and frames, the
// resolve over them on lavapipe (determinism, none ghosting for a resolve that keeps no history)
// and the paper's central ordering, then the command's outputs and its refusals. The resolve's
// options against a CPU restatement, and sequences on disk: tests/sequence_resolve_test.cpp.
#include "flip/device_flip.h"
#include "flip/flip.h"
#include "images/image_io.h"
#include "images/texture_cases.h"
#include "reference/cpu_clip.h"
#include "scenes/sprite_scene.h"
#include "temporal/taa_intervals.h"
#include "temporal/taa_measure.h"
#include "temporal/taa_report.h"
#include "temporal/taa_resolve.h"
#include "temporal/taa_shader.h"
#include "tests/gpu_support.h"
#include "tests/test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace kdop {
namespace {
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// The scene's animation and jitter.

TEST(TaaScene, JitterIsTheR2SequenceCenteredOnThePixel) {
    // The plastic number, found here by Newton's method on g^3 = g + 1.
    double g = 1.5;
    for (int i = 0; i < 50; ++i) g -= (g * g * g - g - 1) / (3 * g * g - 1);
    for (std::uint32_t n = 0; n < 10; ++n) {
        const double x = std::fmod(0.5 + n / g, 1.0) - 0.5, y = std::fmod(0.5 + n / (g * g), 1.0) - 0.5;
        EXPECT_NEAR(r2_jitter(n).x, x, 1e-6) << n;
        EXPECT_NEAR(r2_jitter(n).y, y, 1e-6) << n;
        EXPECT_EQ(r2_jitter(n + 10), r2_jitter(n)) << "ten entries, repeated";
        for (std::uint32_t m = 0; m < n; ++m) EXPECT_NE(r2_jitter(n), r2_jitter(m));
    }
    EXPECT_EQ(r2_jitter(0), glm::vec2(0)) << "the first sample is the pixel's center";
}

TEST(TaaScene, ObjectsMoveSmoothlyOnlyWhenAnimated) {
    const std::uint32_t w = 320, h = 180;
    const FrameState first = frame_state(0, w, h, false, true), later = frame_state(57, w, h, false, true);
    EXPECT_EQ(first.car_center, later.car_center);
    EXPECT_EQ(later.car_motion, glm::vec2(0));
    EXPECT_EQ(later.shadow_motion, glm::vec2(0));
    EXPECT_NE(later.jitter, glm::vec2(0));
    EXPECT_EQ(frame_state(57, w, h, true, false).jitter, glm::vec2(0));

    float fastest = 0;
    for (std::uint32_t f = 1; f < 400; ++f) {
        const FrameState s = frame_state(f, w, h, true, false), before = frame_state(f - 1, w, h, true, false);
        EXPECT_NEAR(glm::distance(s.car_motion, s.car_center - before.car_center), 0, 1e-3) << f;
        EXPECT_NEAR(glm::distance(s.shadow_motion, s.shadow_center - before.shadow_center), 0, 1e-3) << f;
        fastest = std::max({fastest, glm::length(s.car_motion), glm::length(s.shadow_motion)});
    }
    EXPECT_GT(fastest, 0.01f * w) << "fast enough to leave a trail";
    EXPECT_LT(fastest, 0.02f * w) << "no jumps";
}

TEST(TaaScene, ABackgroundOutsideTheUnitRangeIsRefused) {
    test::TempDir dir;
    Image bright(8, 8, {0.5f, 0.5f, 0.5f, 1});
    bright.at(3, 5) = {0.5f, 1.5f, 0.5f, 1};
    const std::string path = (dir / "bright.exr").string();
    ASSERT_TRUE(write_image(path, bright));
    auto scene = read_sprite_scene(path, 16, 16);
    ASSERT_FALSE(scene);
    EXPECT_NE(scene.error().message.find(path + ": pixel (3, 5) has G 1.5, outside [0, 1]"), std::string::npos)
        << scene.error().message;
    EXPECT_FALSE(read_sprite_scene((dir / "missing.png").string(), 16, 16));

    bright.at(3, 5) = {0.5f, 0.5f, 0.5f, 1};
    ASSERT_TRUE(write_image(path, bright));
    auto ok = read_sprite_scene(path, 20, 12);
    ASSERT_TRUE(ok) << ok.error().message;
    EXPECT_EQ(ok->name(), "bright");
    EXPECT_EQ(ok->background().width, 20u) << "tiled to the frame";
}

// A time is within noise of the fastest where the difference is no more than the larger of the two
// interquartile ranges.
// A resolve's output goes to FLIP only within its range: float rounding beyond it (1e-4, scaled by
// the pixel's largest channel for HDR) is moved onto the range, anything further is an error
// naming the pixel, whatever the range.
TEST(TaaMeasure, AnOutputIsCheckedAgainstItsRange) {
    auto one = [](glm::vec4 pixel, ColorRange range) {
        Image image(3, 2, glm::vec4(0.5f, 0.5f, 0.5f, 1));
        image.at(2, 1) = pixel;
        return within_range(image, range, "frame 7");
    };
    auto kept = one({1.00005f, -0.00005f, 0.3f, 1}, ColorRange::ldr);
    ASSERT_TRUE(kept) << kept.error().message;
    EXPECT_EQ(kept->at(2, 1), glm::vec4(1, 0, 0.3f, 1));
    auto bright = one({5000, -0.4f, 20, 1}, ColorRange::hdr);
    ASSERT_TRUE(bright) << bright.error().message;
    EXPECT_EQ(bright->at(2, 1), glm::vec4(5000, 0, 20, 1)) << "-0.4 is rounding beside 5000";
    const struct {
        glm::vec4 pixel;
        ColorRange range;
        const char* message;
    } refused[] = {
        {{1.5f, 0, 0, 1}, ColorRange::ldr, "frame 7: pixel (2, 1) has R 1.5, outside [0, 1] by more than rounding"},
        {{0, -0.01f, 0, 1}, ColorRange::ldr, "pixel (2, 1) has G -0.01, outside [0, 1]"},
        {{0.5f, 0, -0.01f, 1}, ColorRange::hdr, "frame 7: pixel (2, 1) has B -0.01, outside [0, inf)"},
        {{INFINITY, 0, 0, 1}, ColorRange::hdr, "pixel (2, 1) has R inf, outside [0, inf)"},
        {{0, NAN, 0, 1}, ColorRange::hdr, "pixel (2, 1) has G nan"},
    };
    for (const auto& r : refused) {
        auto checked = one(r.pixel, r.range);
        ASSERT_FALSE(checked) << r.message;
        EXPECT_NE(checked.error().message.find(r.message), std::string::npos) << checked.error().message;
    }
}

// A frame's figures by MetricId: its ghosting and shimmer, nothing else measured.
std::vector<double> figures(double ghosting, double shimmer) {
    std::vector<double> values(kBuiltinMetrics, NAN);
    values[kGhosting] = ghosting, values[kShimmer] = shimmer;
    return values;
}

TEST(TaaReport, MarksTimesWithinNoiseOfTheFastest) {
    auto row = [](double ms, double q1, double q3) {
        TaaRow r;
        r.key = VariantKey{"aabb", Mode::clip, Neighborhood::n9};
        r.ms = ms;
        r.ms_q1 = q1;
        r.ms_q3 = q3;
        return r;
    };
    const std::vector<TaaRow> rows{row(1.0, 0.9, 1.2), row(1.25, 1.2, 1.3), row(1.35, 1.3, 1.4), row(NAN, NAN, NAN)};
    EXPECT_TRUE(within_noise_of_fastest(rows[0], rows)) << "the fastest itself";
    EXPECT_TRUE(within_noise_of_fastest(rows[1], rows)) << "0.25 apart, the fastest's spread 0.3";
    EXPECT_FALSE(within_noise_of_fastest(rows[2], rows)) << "0.35 apart";
    EXPECT_FALSE(within_noise_of_fastest(rows[3], rows)) << "not measured";
    const std::string csv = taa_table(rows, default_metrics()).csv();
    EXPECT_NE(csv.find(",1.25,1.2,1.3,1,"), std::string::npos) << csv;
    EXPECT_NE(csv.find(",1.35,1.3,1.4,0,"), std::string::npos) << csv;
}

// Each row's shimmer and ghosting get the block bootstrap of its own frames (a kdop scene's shimmer
// from its -shimmer sequence, its ghosting from its -ghosting one), drawn alike for the variants of
// one scene, and ghosting_noise says whether the paired difference from the least ghosting holds 0;
// a scene of too few frames gets none. The intervals are those bootstrap_replicates gives on the
// same figures, recomputed here from the frame rows.
TEST(TaaReport, IntervalsAreTheBlockBootstrapOfEachRowsFrames) {
    const VariantKey keys[3] = {{"aabb", Mode::clip, Neighborhood::n9},
                                {"dop32", Mode::clip, Neighborhood::n9},
                                {"ycocg", Mode::clip, Neighborhood::n9}};
    std::vector<TaaFrameRow> frames;
    std::vector<std::vector<std::vector<double>>> ghosting(3, {{}}), shimmer(3, {{}});
    for (std::size_t f = 0; f < 24; ++f) {
        const double g = 0.02 + 0.001 * double(f % 5), sh = 0.01 + 0.0005 * double(f % 3);
        // dop32 ghosts 0.003 less than aabb on every frame: beyond noise; ycocg wobbles around dop32: within it.
        const double values[3] = {g, g - 0.003, g - 0.003 + (f % 2 ? 0.0004 : -0.0004)};
        for (std::size_t v = 0; v < 3; ++v) {
            frames.push_back({keys[v], "grass", "grass-ghosting", 100 + f, figures(values[v], NAN)});
            frames.push_back({keys[v], "grass", "grass-shimmer", 100 + f, figures(NAN, sh + 0.001 * double(v))});
            ghosting[v][0].push_back(values[v]);
            shimmer[v][0].push_back(sh + 0.001 * double(v));
        }
    }
    frames.push_back({keys[0], "short", "short", 0, figures(0.5, 0.5)});
    std::vector<TaaRow> rows(4);
    for (TaaRow& row : rows) row.figures.resize(kBuiltinMetrics);
    for (std::size_t v = 0; v < 3; ++v) {
        rows[v].key = keys[v], rows[v].scene = "grass", rows[v].figures[kGhosting].mean = 0;
        for (double x : ghosting[v][0]) rows[v].figures[kGhosting].mean += x / 24;
    }
    rows[1].figures[kGhosting].mean -= 1e-9; // dop32 the least, whatever the rounding of the sums
    rows[3].key = keys[0], rows[3].scene = "short";
    const BootstrapOptions options{4, 500, 3, 0.95};
    add_intervals(rows, frames, kBuiltinMetrics, options);
    const auto g = *bootstrap_replicates(ghosting, options), s = *bootstrap_replicates(shimmer, options);
    for (std::size_t v = 0; v < 3; ++v) {
        SCOPED_TRACE(v);
        const Interval &ghosting_interval = rows[v].figures[kGhosting].interval,
                       &shimmer_interval = rows[v].figures[kShimmer].interval;
        EXPECT_EQ(ghosting_interval.low, percentile_interval(g[v], 0.95).low);
        EXPECT_EQ(ghosting_interval.high, percentile_interval(g[v], 0.95).high);
        EXPECT_EQ(shimmer_interval.low, percentile_interval(s[v], 0.95).low);
        EXPECT_EQ(shimmer_interval.high, percentile_interval(s[v], 0.95).high);
        EXPECT_LT(ghosting_interval.low, ghosting_interval.high);
    }
    EXPECT_EQ(rows[0].within_noise, false) << "0.003 more than the least on every frame";
    EXPECT_EQ(rows[1].within_noise, true) << "the least itself";
    EXPECT_EQ(rows[2].within_noise, true) << "+-0.0004 around the least, frame by frame";
    EXPECT_FALSE(rows[3].figures[kGhosting].interval.known()) << "one frame";
    EXPECT_FALSE(rows[3].within_noise);
    const auto csv = test::csv_rows(taa_table(rows, default_metrics()).csv());
    EXPECT_EQ(csv[0].at("ghosting_noise"), "0");
    EXPECT_EQ(csv[2].at("ghosting_noise"), "1");
    EXPECT_FALSE(csv[0].at("shimmer_low").empty());
    EXPECT_TRUE(csv[3].at("ghosting_low").empty());
}

// The report sets kdop's figures beside the paper's Tables 1 and 2, by rank.
TEST(TaaReport, SetsTheFiguresBesideThePapersTables) {
    const std::pair<const char*, Mode> methods[] = {
        {"aabb", Mode::clip},    {"ycocg", Mode::clip},    {"dop32", Mode::clip},   {"dop16-grass", Mode::clip},
        {"aabb", Mode::varclip}, {"ycocg", Mode::varclip}, {"dop32", Mode::varclip}};
    std::vector<TaaRow> rows;
    auto row = [](const char* set, Mode mode, const char* scene, double shimmer, double ghosting) {
        TaaRow r;
        r.key = VariantKey{set, mode, Neighborhood::n9};
        r.scene = scene;
        r.ms = 1.0;
        r.figures.resize(kBuiltinMetrics);
        r.figures[kShimmer].mean = shimmer;
        r.figures[kGhosting].mean = ghosting;
        return r;
    };
    for (int i = 0; i < 7; ++i) // ghosting rises down the paper's list, shimmer falls
        rows.push_back(row(methods[i].first, methods[i].second, "grass", 0.01 * (7 - i), 0.01 * (i + 1)));
    rows.push_back(row("dop22", Mode::clip, "colobot-grass", 0.5, 0.5));
    const std::string md = taa_report_markdown(rows, describe_run(), {320, 180, 100, 100, 67.0, {}});
    EXPECT_NE(md.find("Beside Table 1 of the paper"), std::string::npos) << md;
    EXPECT_NE(md.find("| RGB | aabb-clip-n9 | 0.0346 (#2) | 0.0700 (#7) | 0.0499 (#6) | 0.0100 (#1) |"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("- Least ghosting: paper 32-DOP+Var, kdop RGB."), std::string::npos) << md;
    EXPECT_NE(md.find("- Most shimmer: paper 32-DOP+Var, kdop RGB."), std::string::npos) << md;
    EXPECT_NE(md.find("- YCoCg over RGB, ghosting: paper 1.08x, kdop 2.00x"), std::string::npos) << md;
    EXPECT_EQ(md.find("Beside Table 2"), std::string::npos) << "no asphalt rows, no Table 2";

    rows.erase(rows.begin() + 3); // without 16-DOP+Opt the paper's table has no counterpart
    EXPECT_EQ(taa_report_markdown(rows, describe_run(), {}).find("Beside Table 1"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// The frames a scene gives the resolve, and the resolve over them on the device (each option
// against a CPU restatement: tests/sequence_resolve_test.cpp).

TEST(TaaScene, DrawsTheObjectsWithTheirMotionAndDepth) {
    constexpr std::uint32_t w = 96, h = 54;
    const Image background = make_texture(TextureFamily::grass, w, h, 1);
    const FrameState s = frame_state(30, w, h, true, false);
    const LoadedFrame frame = render_scene(background, s);
    auto pixel = [&](glm::vec2 at) { return std::size_t(at.y) * w + std::size_t(at.x); };
    const std::size_t car = pixel(s.car_center), shadow = pixel(s.shadow_center), corner = 0;
    EXPECT_EQ(glm::vec3(frame.color.pixels[car]), glm::vec3(0.62f, 0.018f, 0.012f));
    EXPECT_EQ(frame.motion[car], -s.car_motion) << "the box was at x - its motion last frame";
    EXPECT_EQ(frame.depth->pixels[car].r, 0.5f);
    EXPECT_EQ(glm::vec3(frame.color.pixels[shadow]), glm::vec3(0.012f, 0.011f, 0.010f));
    EXPECT_EQ(frame.motion[shadow], -s.shadow_motion);
    EXPECT_EQ(frame.depth->pixels[shadow].r, 1.0f);
    EXPECT_EQ(frame.motion[corner], glm::vec2(0)) << "the background stands still";
    // The background, minified by 1.25 texels per pixel: pixel (0, 0)'s center is texel 0.125.
    const glm::vec3 expected =
        glm::mix(glm::vec3(background.at(0, 0)), glm::vec3(background.at(1, 0)), 0.125f) * 0.875f +
        glm::mix(glm::vec3(background.at(0, 1)), glm::vec3(background.at(1, 1)), 0.125f) * 0.125f;
    EXPECT_LT(glm::distance(glm::vec3(frame.color.pixels[corner]), expected), 1e-6f);
}

using TaaGpu = test::ValidationChecked;

std::unique_ptr<RunnableVariant> taa_shader(const std::string& set, Mode mode) {
    auto axes = resolve_axis_set(set);
    EXPECT_TRUE(axes);
    VariantSpec spec{*axes, mode, Neighborhood::n9};
    auto shader = build_taa_shader(spec);
    EXPECT_TRUE(shader) << shader.error().message;
    return shader ? std::move(*shader) : nullptr;
}

std::unique_ptr<TaaResolve> make_resolve(const RunnableVariant& shader, std::uint32_t w, std::uint32_t h) {
    auto resolve = TaaResolve::create(test::gpu(), shader.variant(), w, h, {});
    EXPECT_TRUE(resolve) << resolve.error().message;
    return resolve ? std::move(*resolve) : nullptr;
}

TEST_F(TaaGpu, TheSameSequenceGivesTheSameFrames) {
    const SceneFrames frames("asphalt", make_texture(TextureFamily::asphalt, 48, 32, 5), 13, true, true);
    auto shader = taa_shader("dop16-asphalt", Mode::varclip);
    ASSERT_TRUE(shader);
    std::vector<Image> runs;
    for (int run = 0; run < 2; ++run) {
        auto resolve = make_resolve(*shader, 48, 32);
        ASSERT_TRUE(resolve);
        const Image* out = nullptr;
        for (std::size_t f = 0; f < frames.frame_count(); ++f) {
            auto resolved = resolve->advance(*frames.frame(f), frames.starts_history(f));
            ASSERT_TRUE(resolved);
            out = *resolved;
        }
        runs.push_back(*out);
    }
    EXPECT_EQ(std::memcmp(runs[0].pixels.data(), runs[1].pixels.data(), runs[0].pixels.size() * sizeof(glm::vec4)), 0);
}

// kdop taa's one pass (every variant resolved on each frame as it is drawn, each against its own
// history) gives each variant exactly the figures and trail frame of a pass of its own.
TEST_F(TaaGpu, OnePassOverTheFramesGivesEachVariantTheFiguresOfItsOwnPass) {
    constexpr std::uint32_t w = 64, h = 36;
    const SpriteScene scene("grass", make_texture(TextureFamily::grass, w, h, 3));
    const HdrFlip flip(pixels_per_degree(ViewingConditions{}));
    const TaaSchedule schedule{10, 6};
    std::vector<std::unique_ptr<RunnableVariant>> shaders;
    shaders.push_back(taa_shader("aabb", Mode::clip));
    shaders.push_back(taa_shader("dop32", Mode::clip));
    shaders.push_back(taa_shader("dop16-grass", Mode::varclip));
    std::vector<const Variant*> variants;
    for (const auto& shader : shaders) {
        ASSERT_TRUE(shader);
        variants.push_back(&shader->variant());
    }
    auto all = TaaResolve::create(test::gpu(), variants, w, h, {});
    ASSERT_TRUE(all) << all.error().message;
    std::size_t frames = 0;
    auto together = measure_scene_all(**all, scene, schedule, *cpu_flip_evaluator(flip), {}, [&] {
        ++frames;
        return Result<void>{};
    });
    ASSERT_TRUE(together) << together.error().message;
    EXPECT_EQ(frames, 2u * (schedule.warmup + schedule.frames)) << "each frame drawn once";
    ASSERT_EQ(together->size(), shaders.size());
    for (std::size_t s = 0; s < shaders.size(); ++s) {
        auto alone_resolve = make_resolve(*shaders[s], w, h);
        ASSERT_TRUE(alone_resolve);
        auto alone = measure_scene(*alone_resolve, scene, schedule, *cpu_flip_evaluator(flip));
        ASSERT_TRUE(alone) << alone.error().message;
        const TaaMeasurement& t = (*together)[s];
        EXPECT_EQ(t.mean(kShimmer), alone->mean(kShimmer)) << variants[s]->name;
        EXPECT_EQ(t.mean(kGhosting), alone->mean(kGhosting)) << variants[s]->name;
        ASSERT_EQ(t.trail.pixels.size(), alone->trail.pixels.size());
        EXPECT_EQ(std::memcmp(t.trail.pixels.data(), alone->trail.pixels.data(), t.trail.pixels.size() * 16), 0);
    }
    EXPECT_NE((*together)[0].mean(kGhosting), (*together)[1].mean(kGhosting)) << "each variant has its own history";
}

// A resolve whose rectification throws the history away shows the aliased frame every frame: no
// ghosting at all, and the most shimmer, which a k-DOP clip's history must reduce.
TEST_F(TaaGpu, KeepingNoHistoryLeavesNoGhostButShimmers) {
    constexpr std::uint32_t w = 64, h = 36;
    const Image background = make_texture(TextureFamily::grass, w, h, 4);
    const HdrFlip flip(pixels_per_degree(ViewingConditions{}));
    auto current_only = build_taa_shader("#define KDOP_NEIGHBORS 9\n"
                                         "vec3 kdop_rectify(vec3 current, vec3 history, float gamma, vec3 n[9])\n"
                                         "{\n    return current;\n}\n",
                                         "taa-current-only");
    ASSERT_TRUE(current_only) << current_only.error().message;
    auto dop32 = taa_shader("dop32", Mode::clip);
    ASSERT_TRUE(dop32);
    const TaaSchedule schedule{12, 6};
    auto none_resolve = make_resolve(**current_only, w, h);
    auto dop32_resolve = make_resolve(*dop32, w, h);
    ASSERT_TRUE(none_resolve && dop32_resolve);
    auto none = measure_scene(*none_resolve, SpriteScene("grass", background), schedule, *cpu_flip_evaluator(flip));
    auto clipped = measure_scene(*dop32_resolve, SpriteScene("grass", background), schedule, *cpu_flip_evaluator(flip));
    ASSERT_TRUE(none && clipped);
    EXPECT_EQ(none->mean(kGhosting), 0.0);
    EXPECT_GT(none->mean(kShimmer), 0.0);
    EXPECT_LT(clipped->mean(kShimmer), none->mean(kShimmer));
    EXPECT_GT(clipped->mean(kGhosting), 0.0) << "a history that is kept lags the moving objects";
}

// The paper's point: on grass (high-frequency chroma and luma) the box lets the objects' colors
// through where a k-DOP does not.
TEST_F(TaaGpu, ADop32GhostsLessThanTheBoxOnGrass) {
    constexpr std::uint32_t w = 96, h = 54;
    const Image background = make_texture(TextureFamily::grass, w, h, 1);
    const HdrFlip flip(pixels_per_degree(ViewingConditions{}));
    const TaaSchedule schedule{40, 12};
    double ghosting[2];
    int i = 0;
    for (const char* set : {"aabb", "dop32"}) {
        auto shader = taa_shader(set, Mode::clip);
        ASSERT_TRUE(shader);
        auto resolve = make_resolve(*shader, w, h);
        ASSERT_TRUE(resolve);
        auto m = measure_scene(*resolve, SpriteScene("grass", background), schedule, *cpu_flip_evaluator(flip));
        ASSERT_TRUE(m) << m.error().message;
        ghosting[i++] = m->mean(kGhosting);
    }
    EXPECT_LT(ghosting[1], ghosting[0]) << "dop32 " << ghosting[1] << ", aabb " << ghosting[0];
}

// kdop taa measures on the device (flip/device_flip.h): the figures are the CPU code's, within
// DeviceFlip's tolerance of 1e-6 relative per mean, and, with the outputs measured where the
// resolve leaves them, bit for bit those of the same FLIP fed outputs read back (the trail
// picture's frame too).
TEST_F(TaaGpu, TheDeviceMeasuresWhatTheCpuMeasures) {
    constexpr std::uint32_t w = 64, h = 36;
    const Image background = make_texture(TextureFamily::grass, w, h, 2);
    const double ppd = pixels_per_degree(ViewingConditions{});
    const HdrFlip flip(ppd);
    auto device = DeviceFlip::create(test::gpu(), ppd, w, h);
    ASSERT_TRUE(device) << device.error().message;
    auto shader = taa_shader("dop16-grass", Mode::clip);
    ASSERT_TRUE(shader);
    const TaaSchedule schedule{8, 5};
    TaaMeasurement m[3];
    const std::unique_ptr<FlipEvaluator> evaluators[] = {
        cpu_flip_evaluator(flip), device_flip_evaluator(**device),
        device_flip_evaluator(**device, {}, OutputPlacement::host)}; // the same FLIP, fed from the host
    for (int i = 0; i < 3; ++i) {
        auto resolve = make_resolve(*shader, w, h);
        ASSERT_TRUE(resolve);
        auto measured = measure_scene(*resolve, SpriteScene("grass", background), schedule, *evaluators[i]);
        ASSERT_TRUE(measured) << measured.error().message;
        m[i] = std::move(*measured);
    }
    ASSERT_GT(m[0].mean(kShimmer), 0.0);
    ASSERT_GT(m[0].mean(kGhosting), 0.0);
    EXPECT_NEAR(m[1].mean(kShimmer), m[0].mean(kShimmer), 1e-6 * m[0].mean(kShimmer));
    EXPECT_NEAR(m[1].mean(kGhosting), m[0].mean(kGhosting), 1e-6 * m[0].mean(kGhosting));
    EXPECT_EQ(m[1].mean(kShimmer), m[2].mean(kShimmer));
    EXPECT_EQ(m[1].mean(kGhosting), m[2].mean(kGhosting));
    ASSERT_EQ(m[1].trail.pixels.size(), m[2].trail.pixels.size());
    EXPECT_GT(m[1].trail.pixels.size(), 0u);
    EXPECT_EQ(std::memcmp(m[1].trail.pixels.data(), m[2].trail.pixels.data(), m[1].trail.pixels.size() * 16), 0);
}

// ---------------------------------------------------------------------------------------------
// kdop taa

struct TaaRun {
    test::TempDir dir;
    // A run small enough for a test: 64x36 frames, 3 frames of warm-up, 2 measured.
    test::CommandResult kdop(const std::string& args, const std::string& size = "64x36") const {
        return test::run(test::kdop_binary() + " taa --size " + size + " --warmup 3 --frames 2 --timing-rounds 2 " +
                         args);
    }
};

TEST(CliTaa, WritesTheTableFramesAndAPicturePerScene) {
    TaaRun t;
    const fs::path out = t.dir / "taa";
    auto r = t.kdop("--sets aabb dop22 --modes clip --scenes grass asphalt --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string csv = test::read_file(out / "taa.csv");
    EXPECT_EQ(
        csv.substr(0, csv.find('\n')),
        "variant,axis_set,mode,neighborhood,scene,upscale,ms,ms_q1,ms_q3,ms_noise,shimmer,shimmer_median,shimmer_p95,"
        "shimmer_low,shimmer_high,ghosting,ghosting_median,ghosting_p95,ghosting_low,ghosting_high,ghosting_noise,"
        "worst_ghosting_frame,worst_shimmer_frame,ghosting_against,flip");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5) << "2 variants x 2 scenes:\n" << csv;
    EXPECT_NE(csv.find("\ndop22-clip-n9,dop22,clip,n9,asphalt,1,"), std::string::npos) << csv;
    for (const char* scene : {"grass", "asphalt"}) {
        EXPECT_TRUE(fs::exists(out / fmt::format("ghosting-{}.png", scene)));
        for (const char* frame : {"aliased", "aabb-clip-n9", "dop22-clip-n9"})
            for (const char* extension : {".exr", ".png"})
                EXPECT_TRUE(fs::exists(out / "frames" / scene / (std::string(frame) + extension))) << frame;
    }
    EXPECT_TRUE(fs::exists(out / "taa.json"));
    const std::string report = test::read_file(out / "report.md");
    EXPECT_NE(report.find("![grass](ghosting-grass.png)"), std::string::npos);
    for (const char* scene : {"grass", "asphalt"}) {
        EXPECT_EQ(test::read_file(out / fmt::format("trade-{}.png", scene)).substr(0, 4), "\x89PNG") << scene;
        EXPECT_NE(report.find(fmt::format("![cost against ghosting and shimmer, {0}](trade-{0}.png)", scene)),
                  std::string::npos)
            << report;
    }
    EXPECT_NE(report.find("| median (ms) | Q1 (ms) | Q3 (ms) | ms within noise of the fastest |"), std::string::npos)
        << report;
}

// With no scene named, the 3-D testbed's two, each beside its table of the paper: ranks, rank
// correlations and how far each method's ghosting is from the paper's.
TEST(CliTaa, TheDefaultScenesAreThe3dTestbedBesideThePaper) {
    TaaRun t;
    const fs::path out = t.dir / "taa";
    auto r = t.kdop("--sets aabb ycocg dop32 dop16-grass dop16-asphalt --modes clip varclip --no-charts --out " +
                    out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string csv = test::read_file(out / "taa.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 21) << "10 variants x 2 scenes:\n" << csv;
    const std::string report = test::read_file(out / "report.md");
    for (const char* scene : {"grass3d", "asphalt3d"}) {
        EXPECT_NE(csv.find(fmt::format("\ndop32-varclip-n9,dop32,varclip,n9,{},", scene)), std::string::npos) << csv;
        EXPECT_TRUE(fs::exists(out / fmt::format("ghosting-{}.png", scene)));
        EXPECT_NE(report.find(fmt::format("## {}\n\nThe scene: 3-D, rasterized on the device", scene)),
                  std::string::npos)
            << report;
    }
    for (const char* table : {"Beside Table 1 of the paper", "Beside Table 2 of the paper"})
        EXPECT_NE(report.find(table), std::string::npos) << report;
    std::size_t correlations = 0;
    for (std::size_t at = 0;
         (at = report.find("Spearman's rank correlation with the paper's column: shimmer ", at)) != std::string::npos;
         ++at)
        ++correlations;
    EXPECT_EQ(correlations, 2u) << report;
    EXPECT_NE(report.find("| kdop / paper ghosting |"), std::string::npos) << report;
}

// A scene's own variants: a manifest naming a user's set, on a user's background.
TEST(CliTaa, TakesAManifestAndTheUsersBackground) {
    TaaRun t;
    // The set file beside the manifest: a manifest reads axis files from its own folder only.
    fs::copy_file(test::data_path("tiny.axes"), t.dir / "tiny.axes");
    test::write_file(t.dir / "scene.manifest", "set: tiny.axes\ntiny-varclip-n9\nycocg-clip-n9\n");
    const std::string background = (t.dir / "meadow.exr").string();
    ASSERT_TRUE(write_image(background, make_texture(TextureFamily::grass, 40, 30, 9)));
    const fs::path out = t.dir / "taa";
    auto r = t.kdop("--manifest " + (t.dir / "scene.manifest").string() + " --background " + background + " --out " +
                    out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string csv = test::read_file(out / "taa.csv");
    EXPECT_NE(csv.find("\ntiny-varclip-n9,tiny,varclip,n9,meadow,"), std::string::npos) << csv;
    EXPECT_NE(csv.find("\nycocg-clip-n9,ycocg,clip,n9,meadow,"), std::string::npos) << csv;
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3) << "only the background given, no built-in scene";
    EXPECT_TRUE(fs::exists(out / "ghosting-meadow.png"));
}

TEST(CliTaa, RefusesBadInputAndWritesNothing) {
    TaaRun t;
    Image bright(8, 8, {2.0f, 0.5f, 0.5f, 1});
    const std::string hdr = (t.dir / "hdr.exr").string();
    ASSERT_TRUE(write_image(hdr, bright));
    const struct {
        std::string args, message;
        int exit_code;
        std::string size = "64x36";
    } cases[] = {
        {"--scenes meadow", "--scenes: no scene 'meadow'; the built-in scenes here: grass3d, asphalt3d, grass, asphalt",
         1},
        {"--scenes grass --camera pan", "--camera: only the 3-D scenes (grass3d, asphalt3d) take it", 2},
        {"--background " + hdr + " --reference-samples 4", "--reference-samples: only the 3-D scenes", 2},
        {"--camera tilt", "--camera", 2},
        {"--background " + (t.dir / "missing.png").string(), "--background: ", 1},
        {"--background " + hdr, "hdr.exr: pixel (0, 0) has R 2, outside [0, 1]", 1},
        {"", "--size: '4x4' is not WIDTHxHEIGHT", 2, "4x4"},
        {"--frames 0", "--frames", 2},
        {"--ppd -3", "--ppd: '-3' is not a number from 1 to 1000", 2},
        {"--ppd 0.5", "--ppd: '0.5' is not a number from 1 to 1000", 2},
        {"--baselines", "--baselines: the gather and copy baselines are not clips", 1},
        {"--sets nowhere.axes", "nowhere.axes", 2},
    };
    for (const auto& c : cases) {
        const fs::path out = t.dir / "out";
        auto r = t.kdop(c.args + " --out " + out.string(), c.size);
        EXPECT_EQ(r.exit_code, c.exit_code) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
        EXPECT_FALSE(fs::exists(out)) << c.args;
    }
}

} // namespace
} // namespace kdop
