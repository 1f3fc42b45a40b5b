// The 3-D testbed (testbed/): rasterized on lavapipe with the validation layer on, its samples,
// depth and motion checked against what the camera and the scene's transforms say, independently
// of the shaders that drew them.
#include "flip/device_flip.h"
#include "flip/flip.h"
#include "flip/hdr_flip.h"
#include "sequence/jitter.h"
#include "temporal/taa_measure.h"
#include "temporal/taa_resolve.h"
#include "temporal/taa_shader.h"
#include "testbed/camera.h"
#include "testbed/scene3d.h"
#include "testbed/scene3d_frames.h"
#include "testbed/testbed_renderer.h"
#include "tests/gpu_support.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

namespace kdop {
namespace {

class Testbed : public test::ValidationChecked {};

std::unique_ptr<TestbedRenderer> renderer(Scene3d scene, std::uint32_t w, std::uint32_t h) {
    auto r = TestbedRenderer::create(test::gpu(), std::make_shared<const Scene3d>(std::move(scene)), w, h);
    EXPECT_TRUE(r) << r.error().message;
    return r ? std::move(*r) : nullptr;
}

// A rectangle in the plane through `center` spanned by `u` and `v` (half extents), split into
// n x n quads, each vertex colored by its place on the rectangle: red and green ramps (affine on
// the rectangle) and, with `waves`, blue waves across it, a picture fixed to the surface, so
// that where it moves is visible everywhere on it.
void add_painted_rectangle(Mesh& mesh, glm::vec3 center, glm::vec3 u, glm::vec3 v, int n = 12, bool waves = true) {
    const glm::vec3 normal = glm::normalize(glm::cross(u, v));
    auto vertex = [&](int i, int j) {
        const float s = float(i) / float(n), t = float(j) / float(n);
        const float blue = waves ? 0.5f + 0.3f * float(std::sin(2 * std::numbers::pi * (s + t))) : 0.5f;
        return MeshVertex{center + (2 * s - 1) * u + (2 * t - 1) * v, normal,
                          glm::vec3(0.15f + 0.7f * s, 0.15f + 0.7f * t, blue), 0};
    };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (auto [a, b] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}})
                mesh.push_back(vertex(i + a, j + b));
}

// A wall facing the camera at distance 4, lit head-on: its color is affine on the screen.
Scene3d wall_scene() {
    Scene3d s;
    s.name = "wall";
    s.texture = Image(1, 1, glm::vec4(1));
    add_painted_rectangle(s.still, {0, 0, 4}, {3, 0, 0}, {0, 3, 0}, 1, false);
    s.camera = {{0, 0, 0}, {0, 0, 1}, 0.7f};
    s.sun = {0, 0, -1};
    return s;
}

// A smooth ground (a low-frequency texture) under a painted board that slides and turns, and a
// second that also comes toward the camera: every surface's picture is fixed to it.
Scene3d moving_boards_scene() {
    Scene3d s;
    s.name = "boards";
    s.texture = Image(64, 64);
    for (std::uint32_t y = 0; y < 64; ++y)
        for (std::uint32_t x = 0; x < 64; ++x)
            s.texture.at(x, y) = glm::vec4(0.5f + 0.3f * float(std::sin(8 * std::numbers::pi * x / 64)),
                                           0.5f + 0.3f * float(std::cos(8 * std::numbers::pi * y / 64)), 0.4f, 1);
    s.texture_period = 4;
    add_ground_quad(s.still, 0, {-30, -5}, {30, 60}, glm::vec3(1), true);
    s.moving = [](double t) {
        Mesh m;
        const float a = float(0.04 * t), x = float(0.06 * t);
        add_painted_rectangle(m, {-0.8f + x, 1.0f, 3.0f}, {std::cos(a) * 0.7f, std::sin(a) * 0.7f, 0},
                              {-std::sin(a) * 0.5f, std::cos(a) * 0.5f, 0});
        add_painted_rectangle(m, {1.2f, 0.8f, 4.0f - 0.08f * float(t)}, {0.6f, 0, 0.2f}, {0, 0.6f, 0});
        return m;
    };
    s.camera = {{0, 2.0f, -3.0f}, {0, 0.6f, 3.0f}, 0.8f};
    s.sun = glm::normalize(glm::vec3(0.2f, 1.0f, -0.6f));
    return s;
}

// Jitter through the projection: on the affine wall, the pixel at p jittered by j shows what the
// pixel at p shows unjittered plus j times the color's screen gradient.
TEST_F(Testbed, JitterMovesSamplesByExactlyTheR2Offsets) {
    constexpr std::uint32_t w = 64, h = 48;
    auto r = renderer(wall_scene(), w, h);
    ASSERT_TRUE(r);
    const Camera3d camera = r->scene().camera;
    auto still = r->draw(0, camera, 0, camera, {0, 0});
    ASSERT_TRUE(still);
    for (std::uint32_t k = 1; k < 10; ++k) {
        const glm::vec2 j = r2_jitter(k);
        auto moved = r->draw(0, camera, 0, camera, j);
        ASSERT_TRUE(moved);
        double worst = 0;
        for (std::uint32_t y = 1; y + 1 < h; ++y)
            for (std::uint32_t x = 1; x + 1 < w; ++x) {
                const glm::vec4 c = still->color.at(x, y);
                const glm::vec4 dx = (still->color.at(x + 1, y) - still->color.at(x - 1, y)) * 0.5f;
                const glm::vec4 dy = (still->color.at(x, y + 1) - still->color.at(x, y - 1)) * 0.5f;
                const glm::vec4 expected = c + j.x * dx + j.y * dy;
                for (int ch = 0; ch < 2; ++ch)
                    worst = std::max(worst, double(std::abs(moved->color.at(x, y)[ch] - expected[ch])));
            }
        // One pixel's step is about 0.01; the opposite jitter would be off by up to that.
        EXPECT_LT(worst, 2e-5) << "jitter " << k << " (" << j.x << ", " << j.y << ")";
        // Jitter does not change the motion: nothing moved.
        for (const glm::vec2& m : moved->motion) ASSERT_EQ(m, glm::vec2(0));
    }
}

TEST_F(Testbed, DepthGrowsWithDistance) {
    constexpr std::uint32_t w = 80, h = 60;
    Scene3d scene = moving_boards_scene();
    scene.moving = {};
    // Three walls side by side at distances 3, 6 and 12 from the camera, above the ground.
    for (float d : {3.0f, 6.0f, 12.0f}) {
        const float x = (d - 6.0f) / 3.0f * 0.9f;
        add_painted_rectangle(scene.still, glm::vec3(x * d / 6.0f, 4.0f, d - 3.0f), {0.1f * d, 0, 0}, {0, 0.2f, 0}, 1,
                              false);
    }
    scene.camera = {{0, 4.0f, -3.0f}, {0, 4.0f, 3.0f}, 1.2f};
    auto r = renderer(scene, w, h);
    ASSERT_TRUE(r);
    auto drawn = r->draw(0, scene.camera, 0, scene.camera, {0, 0});
    ASSERT_TRUE(drawn);
    // The ground below the horizon: farther up each column, farther away, so deeper.
    std::size_t compared = 0;
    for (std::uint32_t x = 0; x < w; ++x)
        for (std::uint32_t y = h - 1; y > h / 2 + 6; --y) {
            const float below = drawn->depth[std::size_t(y) * w + x], above = drawn->depth[std::size_t(y - 1) * w + x];
            if (above == 1.0f) break; // beyond the ground's far edge
            ASSERT_LT(below, above) << "column " << x << ", row " << y;
            ++compared;
        }
    EXPECT_GT(compared, 1000u);
    // The walls at the height of the camera, read along the middle row.
    std::vector<float> seen;
    const std::uint32_t row = h / 2;
    for (std::uint32_t x = 0; x < w; ++x) {
        const float d = drawn->depth[std::size_t(row) * w + x];
        if (d < 1.0f && (seen.empty() || std::abs(seen.back() - d) > 1e-4f)) seen.push_back(d);
    }
    ASSERT_EQ(seen.size(), 3u) << "the three walls along the middle row";
    // Each is the depth the projection gives one wall's distance: nearer, smaller.
    std::sort(seen.begin(), seen.end());
    for (int i = 0; i < 3; ++i) {
        const float distance = 3.0f * float(1 << i);
        const glm::vec4 clip = view_projection(scene.camera, w, h) * glm::vec4(0, 4.0f, distance - 3.0f, 1);
        EXPECT_NEAR(seen[i], clip.z / clip.w, 1e-5) << "the wall at " << distance;
    }
}

// Frame t-1 sampled (bilinear) where frame t's motion points, against frame t, on the pixels that
// moved more than a quarter pixel and whose surface both frames show away from its edges: no depth
// step in the pixel's 3x3 neighborhood now or in the texels the warp reads then.
struct WarpCheck {
    double within = 0; // the share of those pixels warped within tolerance
    std::size_t moved = 0;
};

// Whether depth is continuous over the texels from `low` to `high` (clamped into the image).
bool depth_continuous(const std::vector<float>& depth, std::uint32_t w, std::uint32_t h, glm::ivec2 low,
                      glm::ivec2 high) {
    float least = 1, most = 0;
    for (int y = std::max(low.y, 0); y <= std::min(high.y, int(h) - 1); ++y)
        for (int x = std::max(low.x, 0); x <= std::min(high.x, int(w) - 1); ++x) {
            const float d = depth[std::size_t(y) * w + std::size_t(x)];
            least = std::min(least, d), most = std::max(most, d);
        }
    return most - least < 1e-3f; // steps between the boards and the ground behind them are several times this
}

WarpCheck warp_check(const RasterImages& now, const RasterImages& before, std::uint32_t w, std::uint32_t h,
                     float scale_motion) {
    WarpCheck c;
    std::size_t good = 0;
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) {
            const glm::vec2 m = now.motion[std::size_t(y) * w + x] * scale_motion;
            const glm::vec2 q = glm::vec2(float(x), float(y)) + m;
            if (q.x < 0 || q.y < 0 || q.x > float(w - 1) || q.y > float(h - 1)) continue;
            if (glm::length(now.motion[std::size_t(y) * w + x]) < 0.25f) continue;
            const glm::ivec2 i(glm::floor(q)), p{int(x), int(y)};
            if (!depth_continuous(now.depth, w, h, p - 1, p + 1) || !depth_continuous(before.depth, w, h, i, i + 1))
                continue;
            const glm::vec2 f = q - glm::vec2(i);
            auto at = [&](int dx, int dy) {
                return glm::vec3(before.color.at(std::uint32_t(std::min(i.x + dx, int(w) - 1)),
                                                 std::uint32_t(std::min(i.y + dy, int(h) - 1))));
            };
            const glm::vec3 warped =
                glm::mix(glm::mix(at(0, 0), at(1, 0), f.x), glm::mix(at(0, 1), at(1, 1), f.x), f.y);
            const glm::vec3 error = glm::abs(warped - glm::vec3(now.color.at(x, y)));
            ++c.moved;
            if (std::max({error.r, error.g, error.b}) < 0.03f) ++good;
        }
    c.within = c.moved ? double(good) / double(c.moved) : 0;
    return c;
}

// Warping an earlier frame by frame t's motion back to it reproduces frame t wherever the surface
// was seen in both: boards sliding, turning and coming nearer over a still ground, with the camera
// still and panning, 3 frames apart so that the slow pan moves the ground by pixels. All but the
// pixels at the boards' edges (where a surface appears or disappears) agree; motion halved or
// pointing nowhere does not.
TEST_F(Testbed, WarpingTheLastFrameByTheMotionGivesThisOne) {
    constexpr std::uint32_t w = 160, h = 90;
    auto r = renderer(moving_boards_scene(), w, h);
    ASSERT_TRUE(r);
    for (bool pan : {false, true}) {
        for (double t : {5.0, 12.0}) {
            const double then = t - 3;
            const Camera3d now = camera_at(r->scene(), t, pan), before = camera_at(r->scene(), then, pan);
            auto current = r->draw(t, now, then, before, {0, 0});
            auto previous = r->draw(then, before, then, before, {0, 0});
            ASSERT_TRUE(current && previous);
            const WarpCheck right = warp_check(*current, *previous, w, h, 1.0f);
            const WarpCheck half = warp_check(*current, *previous, w, h, 0.5f);
            const WarpCheck none = warp_check(*current, *previous, w, h, 0.0f);
            EXPECT_GT(right.moved, pan ? 5000u : 300u) << "pan " << pan << ", time " << t;
            EXPECT_GT(right.within, 0.99) << "pan " << pan << ", time " << t;
            EXPECT_LT(half.within, 0.8) << "pan " << pan << ", time " << t;
            EXPECT_LT(none.within, 0.6) << "pan " << pan << ", time " << t;
        }
    }
}

TEST_F(Testbed, TheSameSeedDrawsTheSameFrames) {
    constexpr std::uint32_t w = 96, h = 54;
    std::vector<RasterImages> drawn;
    for (std::uint64_t seed : {3u, 3u, 4u}) {
        for (bool grass : {true, false}) {
            Scene3d scene = grass ? grass3d_scene(seed) : asphalt3d_scene(seed);
            auto r = renderer(scene, w, h);
            ASSERT_TRUE(r);
            const Camera3d c = r->scene().camera;
            auto frame = r->draw(7, c, 6, c, r2_jitter(7));
            ASSERT_TRUE(frame);
            drawn.push_back(std::move(*frame));
        }
    }
    auto same = [&](const RasterImages& a, const RasterImages& b) {
        return std::memcmp(a.color.pixels.data(), b.color.pixels.data(), a.color.pixels.size() * 16) == 0 &&
               std::memcmp(a.motion.data(), b.motion.data(), a.motion.size() * 8) == 0 &&
               std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * 4) == 0;
    };
    EXPECT_TRUE(same(drawn[0], drawn[2])) << "grass3d, seed 3 twice";
    EXPECT_TRUE(same(drawn[1], drawn[3])) << "asphalt3d, seed 3 twice";
    EXPECT_FALSE(same(drawn[0], drawn[4])) << "grass3d, seeds 3 and 4";
    EXPECT_FALSE(same(drawn[1], drawn[5])) << "asphalt3d, seeds 3 and 4";
    // Both scenes keep to LDR, and the objects move where the scene animates them.
    for (const RasterImages& d : drawn) {
        for (const glm::vec4& p : d.color.pixels)
            for (int c = 0; c < 3; ++c) ASSERT_TRUE(p[c] >= 0.0f && p[c] <= 1.0f);
        EXPECT_TRUE(std::any_of(d.motion.begin(), d.motion.end(), [](glm::vec2 m) { return glm::length(m) > 0.5f; }));
    }
}

// Without animation and jitter the testbed's frames are all the same, and a resolve over them
// converges at once: no ghosting at all. Each frame's reference of one sample is the frame itself.
TEST_F(Testbed, AStillSceneWithoutJitterLeavesNoGhost) {
    constexpr std::uint32_t w = 64, h = 36;
    auto r = TestbedRenderer::create(test::gpu(), std::make_shared<const Scene3d>(grass3d_scene(2)), w, h);
    ASSERT_TRUE(r) << r.error().message;
    const Scene3dFrames still("grass3d-still", std::move(*r),
                              {.frames = 8, .animate = false, .jitter = false, .reference_samples = 1});
    auto axes = resolve_axis_set("dop32");
    ASSERT_TRUE(axes);
    auto shader = build_taa_shader(VariantSpec{*axes, Mode::clip, Neighborhood::n9});
    ASSERT_TRUE(shader) << shader.error().message;
    auto resolve = TaaResolve::create(test::gpu(), (*shader)->variant(), w, h, {});
    ASSERT_TRUE(resolve) << resolve.error().message;
    const HdrFlip flip(pixels_per_degree(ViewingConditions{}));
    auto m = measure_sequence(**resolve, still, 3, *cpu_flip_evaluator(flip));
    ASSERT_TRUE(m) << m.error().message;
    EXPECT_TRUE(m->against_reference);
    EXPECT_EQ(m->mean(kGhosting), 0.0);
    EXPECT_EQ(m->mean(kShimmer), 0.0);
    auto frame = still.frame(4);
    ASSERT_TRUE(frame);
    EXPECT_EQ(std::memcmp(frame->color.pixels.data(), frame->reference->pixels.data(), w * h * 16), 0);
    for (const glm::vec2& motion : frame->motion) ASSERT_EQ(motion, glm::vec2(0));
}

// The one pass on a 3-D scene with a panning camera and references: each frame drawn once, every
// variant's figures those of a pass of its own (which draws the frames again).
TEST_F(Testbed, OnePassGivesEachVariantTheFiguresOfItsOwnPass) {
    constexpr std::uint32_t w = 64, h = 36;
    auto r = TestbedRenderer::create(test::gpu(), std::make_shared<const Scene3d>(grass3d_scene(3)), w, h);
    ASSERT_TRUE(r) << r.error().message;
    const Scene3dFrames panning("grass3d-pan", std::move(*r),
                                {.frames = 10, .animate = true, .jitter = false, .pan = true, .reference_samples = 2});
    const HdrFlip flip(pixels_per_degree(ViewingConditions{}));
    std::vector<std::unique_ptr<RunnableVariant>> shaders;
    std::vector<const Variant*> variants;
    for (const char* set : {"aabb", "dop32"}) {
        auto axes = resolve_axis_set(set);
        ASSERT_TRUE(axes);
        auto shader = build_taa_shader(VariantSpec{*axes, Mode::clip, Neighborhood::n9});
        ASSERT_TRUE(shader) << shader.error().message;
        variants.push_back(&(*shader)->variant());
        shaders.push_back(std::move(*shader));
    }
    auto all = TaaResolve::create(test::gpu(), variants, w, h, {});
    ASSERT_TRUE(all) << all.error().message;
    auto together = measure_sequence_all(**all, panning, 4, *cpu_flip_evaluator(flip));
    ASSERT_TRUE(together) << together.error().message;
    for (std::size_t s = 0; s < variants.size(); ++s) {
        auto alone_resolve = TaaResolve::create(test::gpu(), *variants[s], w, h, {});
        ASSERT_TRUE(alone_resolve);
        auto alone = measure_sequence(**alone_resolve, panning, 4, *cpu_flip_evaluator(flip));
        ASSERT_TRUE(alone) << alone.error().message;
        EXPECT_TRUE((*together)[s].against_reference);
        EXPECT_GT((*together)[s].mean(kGhosting), 0.0);
        EXPECT_EQ((*together)[s].mean(kGhosting), alone->mean(kGhosting)) << variants[s]->name;
        EXPECT_EQ((*together)[s].mean(kShimmer), alone->mean(kShimmer)) << variants[s]->name;
    }
}

// `source` as a source that only reads its frames back: every frame through the host, the way the
// measurement took them before frames could stay on the device.
class ReadBackOnly final : public FrameSource {
public:
    explicit ReadBackOnly(const FrameSource& source) : source_(source) {}
    const std::string& name() const override { return source_.name(); }
    std::uint32_t width() const override { return source_.width(); }
    std::uint32_t height() const override { return source_.height(); }
    std::size_t frame_count() const override { return source_.frame_count(); }
    ColorRange color_range() const override { return source_.color_range(); }
    bool starts_history(std::size_t index) const override { return source_.starts_history(index); }
    std::optional<glm::vec2> jitter(std::size_t index) const override { return source_.jitter(index); }
    bool has_depth() const override { return source_.has_depth(); }
    bool has_reference() const override { return source_.has_reference(); }
    Result<LoadedFrame> frame(std::size_t index) const override { return source_.frame(index); }
    std::string frame_label(std::size_t index) const override { return source_.frame_label(index); }

private:
    const FrameSource& source_;
};

// Frames drawn straight into the resolve's inputs (color, motion, and depth for --dilate-motion)
// give every shader the outputs, bit for bit, of the same frames read back and uploaded, the first
// frame (no motion) included, and bring back, when asked, the color and reference frame() reads;
// and the measurement, which draws every frame so, gives the figures of one that reads every frame
// back.
TEST_F(Testbed, FramesDrawnIntoTheResolveGiveTheOutputsOfFramesReadBack) {
    constexpr std::uint32_t w = 64, h = 36;
    auto r = TestbedRenderer::create(test::gpu(), std::make_shared<const Scene3d>(grass3d_scene(3)), w, h);
    ASSERT_TRUE(r) << r.error().message;
    const Scene3dFrames panning("grass3d-pan", std::move(*r),
                                {.frames = 8, .animate = true, .jitter = true, .pan = true, .reference_samples = 2});
    ASSERT_NE(panning.device_frames(), nullptr);
    const ReadBackOnly read_back(panning);
    ASSERT_EQ(read_back.device_frames(), nullptr);
    std::vector<std::unique_ptr<RunnableVariant>> shaders;
    std::vector<const Variant*> variants;
    for (bool dilate : {false, true}) {
        ResolveOptions options;
        options.dilate_motion = dilate;
        shaders.clear(), variants.clear();
        for (const char* set : {"aabb", "dop32"}) {
            auto axes = resolve_axis_set(set);
            ASSERT_TRUE(axes);
            auto shader = build_taa_shader(VariantSpec{*axes, Mode::clip, Neighborhood::n9}, options);
            ASSERT_TRUE(shader) << shader.error().message;
            variants.push_back(&(*shader)->variant());
            shaders.push_back(std::move(*shader));
        }
        auto drawn = TaaResolve::create(test::gpu(), variants, w, h, options);
        auto uploaded = TaaResolve::create(test::gpu(), variants, w, h, options);
        ASSERT_TRUE(drawn && uploaded);
        for (std::size_t i = 0; i < panning.frame_count(); ++i) {
            auto frame = panning.frame(i);
            ASSERT_TRUE(frame) << frame.error().message;
            ASSERT_TRUE((*uploaded)->advance_all(*frame, i == 0));
            const bool read_frame = i % 2 == 1;
            auto back = (*drawn)->advance_all(*panning.device_frames(), i, i == 0, true, read_frame);
            ASSERT_TRUE(back) << back.error().message;
            // What comes back of a frame drawn on the device is its color and reference, as read.
            if (read_frame) {
                ASSERT_EQ(back->color.pixels.size(), frame->color.pixels.size());
                EXPECT_EQ(std::memcmp(back->color.pixels.data(), frame->color.pixels.data(), w * h * 16), 0);
                ASSERT_TRUE(back->reference && frame->reference);
                EXPECT_EQ(std::memcmp(back->reference->pixels.data(), frame->reference->pixels.data(), w * h * 16), 0);
                EXPECT_TRUE(back->motion.empty() && !back->depth);
            } else {
                EXPECT_TRUE(back->color.pixels.empty() && !back->reference);
            }
            for (std::size_t s = 0; s < variants.size(); ++s) {
                const Image &a = (*drawn)->output(s), &b = (*uploaded)->output(s);
                ASSERT_EQ(a.pixels.size(), std::size_t(w) * h);
                EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * 16), 0)
                    << variants[s]->name << ", dilate " << dilate << ", frame " << i;
            }
        }
        const HdrFlip flip(pixels_per_degree(ViewingConditions{}));
        auto all = TaaResolve::create(test::gpu(), variants, w, h, options);
        auto all_read = TaaResolve::create(test::gpu(), variants, w, h, options);
        ASSERT_TRUE(all && all_read);
        auto figures = measure_sequence_all(**all, panning, 4, *cpu_flip_evaluator(flip));
        auto figures_read = measure_sequence_all(**all_read, read_back, 4, *cpu_flip_evaluator(flip));
        ASSERT_TRUE(figures && figures_read);
        for (std::size_t s = 0; s < variants.size(); ++s) {
            EXPECT_GT((*figures)[s].mean(kGhosting), 0.0);
            EXPECT_EQ((*figures)[s].mean(kGhosting), (*figures_read)[s].mean(kGhosting)) << variants[s]->name;
            EXPECT_EQ((*figures)[s].mean(kShimmer), (*figures_read)[s].mean(kShimmer)) << variants[s]->name;
        }
        // And with the device's FLIP: drawn, resolved and measured on the device (outputs loaded
        // where they are), what the same FLIP gives frames and outputs read back and uploaded.
        auto device = DeviceFlip::create(test::gpu(), pixels_per_degree(ViewingConditions{}), w, h);
        ASSERT_TRUE(device) << device.error().message;
        auto from_device = device_flip_evaluator(**device);
        auto from_host = device_flip_evaluator(**device, {}, OutputPlacement::host);
        auto on_device = TaaResolve::create(test::gpu(), variants, w, h, options);
        auto on_host = TaaResolve::create(test::gpu(), variants, w, h, options);
        ASSERT_TRUE(on_device && on_host);
        auto here = measure_sequence_all(**on_device, panning, 4, *from_device);
        auto there = measure_sequence_all(**on_host, read_back, 4, *from_host);
        ASSERT_TRUE(here && there);
        for (std::size_t s = 0; s < variants.size(); ++s) {
            EXPECT_GT((*here)[s].mean(kGhosting), 0.0);
            EXPECT_EQ((*here)[s].mean(kGhosting), (*there)[s].mean(kGhosting)) << variants[s]->name;
            EXPECT_EQ((*here)[s].mean(kShimmer), (*there)[s].mean(kShimmer)) << variants[s]->name;
        }
    }
}

} // namespace
} // namespace kdop
