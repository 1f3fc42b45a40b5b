// The one TAA resolve (shader_templates/taa_resolve.comp.in) over frame sources: each option
// against a CPU restatement of it, the properties the measurements rest on (a still, unjittered
// sequence neither ghosts nor shimmers; a camera cut drops the history; the four motion
// conventions describing one motion resolve bit for bit alike; Catmull-Rom keeps a ramp), and
// `kdop scene` + `kdop taa --sequence`: a replay equals the in-memory run, an HDR sequence is
// measured in HDR-FLIP (the CPU code's figures), bad sequences are refused, naming the file, with
// nothing written.
#include "core/write_files.h"
#include "flip/device_flip.h"
#include "flip/flip.h"
#include "flip/hdr_flip.h"
#include "images/image_io.h"
#include "images/texture_cases.h"
#include "reference/cpu_clip.h"
#include "scenes/sprite_scene.h"
#include "sequence/jitter.h"
#include "sequence/sequence_writer.h"
#include "temporal/taa_measure.h"
#include "temporal/taa_resolve.h"
#include "temporal/taa_shader.h"
#include "tests/gpu_support.h"
#include "tests/test_support.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <memory>

namespace kdop {
namespace {
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// The resolve restated on the CPU, in double, from the template's definition.

struct CpuResolve {
    ResolveOptions o;
    std::vector<glm::dvec3> axes;
    Mode mode;

    glm::dvec3 map(glm::dvec3 c) const {
        switch (o.color_map.kind) {
        case ColorMap::Kind::power: return glm::pow(glm::max(c, 0.0), glm::dvec3(o.color_map.exponent));
        case ColorMap::Kind::log: return glm::log(glm::max(c, 0.0) + 1e-5);
        case ColorMap::Kind::linear: break;
        }
        return c;
    }
    glm::dvec3 unmap(glm::dvec3 m) const {
        switch (o.color_map.kind) {
        case ColorMap::Kind::power: return glm::pow(glm::max(m, 0.0), glm::dvec3(1.0 / o.color_map.exponent));
        case ColorMap::Kind::log: return glm::max(glm::exp(m) - 1e-5, 0.0);
        case ColorMap::Kind::linear: break;
        }
        return m;
    }
    static glm::dvec4 cubic_weights(double f) {
        return {f * (-0.5 + f * (1 - 0.5 * f)), 1 + f * f * (-2.5 + 1.5 * f), f * (0.5 + f * (2 - 1.5 * f)),
                f * f * (-0.5 + 0.5 * f)};
    }
    glm::dvec3 history_at(const Image& h, glm::dvec2 x) const {
        const glm::dvec2 t = x - 0.5, f = t - glm::floor(t);
        const glm::ivec2 i(glm::floor(t));
        auto at = [&](int dx, int dy) { return glm::dvec3(glm::vec3(h.clamped(i.x + dx, i.y + dy))); };
        if (o.history_filter == HistoryFilter::bilinear)
            return glm::mix(glm::mix(at(0, 0), at(1, 0), f.x), glm::mix(at(0, 1), at(1, 1), f.x), f.y);
        const glm::dvec4 wx = cubic_weights(f.x), wy = cubic_weights(f.y);
        glm::dvec3 sum(0);
        for (int b = 0; b < 4; ++b)
            for (int a = 0; a < 4; ++a) sum += wx[a] * wy[b] * at(a - 1, b - 1);
        return glm::max(sum, 0.0);
    }
    // The pixel whose motion (x, y) takes.
    std::size_t motion_source(const LoadedFrame& f, int x, int y) const {
        const int w = int(f.color.width), h = int(f.color.height);
        std::size_t best = std::size_t(y) * w + x;
        if (!o.dilate_motion) return best;
        float nearest = f.depth->pixels[best].r;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const std::size_t q = std::size_t(std::clamp(y + dy, 0, h - 1)) * w + std::clamp(x + dx, 0, w - 1);
                const float d = f.depth->pixels[q].r;
                if (o.depth_nearer_larger ? d > nearest : d < nearest) nearest = d, best = q;
            }
        return best;
    }
    Image frame(const LoadedFrame& f, bool starts_history, const Image& history) const {
        const Image& c = f.color;
        Image out(c.width, c.height);
        for (std::uint32_t y = 0; y < c.height; ++y)
            for (std::uint32_t x = 0; x < c.width; ++x) {
                const glm::dvec3 current(glm::vec3(c.at(x, y)));
                glm::dvec2 previous(x + 0.5, y + 0.5);
                if (!starts_history) previous += glm::dvec2(f.motion[motion_source(f, int(x), int(y))]);
                if (starts_history || previous.x < 0 || previous.y < 0 || previous.x > c.width ||
                    previous.y > c.height) {
                    out.at(x, y) = glm::vec4(glm::vec3(current), 1);
                    continue;
                }
                std::vector<glm::dvec3> neighborhood;
                for (glm::ivec2 d : reference_offsets(Neighborhood::n9))
                    neighborhood.push_back(map(glm::dvec3(glm::vec3(c.clamped(int(x) + d.x, int(y) + d.y)))));
                const glm::dvec3 mc = map(current);
                const glm::dvec3 r =
                    reference_clip(axes, neighborhood, mc, map(history_at(history, previous)), mode, o.gamma);
                out.at(x, y) = glm::vec4(glm::vec3(unmap(r + double(o.current_weight) * (mc - r))), 1);
            }
        return out;
    }
};

std::unique_ptr<RunnableVariant> resolve_shader(const std::string& set, Mode mode, const ResolveOptions& options) {
    auto axes = resolve_axis_set(set);
    EXPECT_TRUE(axes);
    auto shader = build_taa_shader(VariantSpec{*axes, mode, Neighborhood::n9}, options);
    EXPECT_TRUE(shader) << shader.error().message;
    return shader ? std::move(*shader) : nullptr;
}

std::unique_ptr<TaaResolve> make_resolve(const RunnableVariant& shader, std::uint32_t w, std::uint32_t h,
                                         const ResolveOptions& options) {
    auto resolve = TaaResolve::create(test::gpu(), shader.variant(), w, h, options);
    EXPECT_TRUE(resolve) << resolve.error().message;
    return resolve ? std::move(*resolve) : nullptr;
}

// The number of pixels of `a` and `b` farther apart than `tolerance`.
std::size_t pixels_apart(const Image& a, const Image& b, float tolerance) {
    std::size_t off = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        if (glm::distance(glm::vec3(a.pixels[i]), glm::vec3(b.pixels[i])) > tolerance) ++off;
    return off;
}

bool bit_identical(const Image& a, const Image& b) {
    return a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec4)) == 0;
}

using ResolveGpu = test::ValidationChecked;

TEST_F(ResolveGpu, EachOptionMatchesTheCpuRestatement) {
    constexpr std::uint32_t w = 64, h = 40;
    const SceneFrames frames("grass", make_texture(TextureFamily::grass, w, h, 3), 26, true, true);
    ResolveOptions catmull_rom, power, log_map, dilated, heavy;
    catmull_rom.history_filter = HistoryFilter::catmull_rom;
    power.color_map = *parse_color_map("gamma:0.5");
    log_map.color_map = *parse_color_map("log");
    dilated.dilate_motion = true;
    heavy.current_weight = 0.4f;
    heavy.gamma = 1.5f;
    const struct {
        const char* name;
        ResolveOptions options;
        Mode mode;
    } cases[] = {{"defaults", {}, Mode::clip},     {"catmull-rom", catmull_rom, Mode::clip},
                 {"gamma:0.5", power, Mode::clip}, {"log", log_map, Mode::varclip},
                 {"dilate", dilated, Mode::clip},  {"weight 0.4, gamma 1.5", heavy, Mode::varclip}};
    for (const auto& c : cases) {
        auto shader = resolve_shader("dop22", c.mode, c.options);
        ASSERT_TRUE(shader);
        auto resolve = make_resolve(*shader, w, h, c.options);
        ASSERT_TRUE(resolve);
        const CpuResolve cpu{c.options, unit_axes(*resolve_axis_set("dop22")), c.mode};
        Image history;
        for (std::size_t f = 0; f < frames.frame_count(); ++f) {
            auto frame = frames.frame(f);
            ASSERT_TRUE(frame);
            auto gpu = resolve->advance(*frame, frames.starts_history(f));
            ASSERT_TRUE(gpu) << gpu.error().message;
            if (f >= 20) {
                const Image expected = cpu.frame(*frame, false, history);
                // float32 against double, as in the standalone variants' reference test; a history
                // within rounding of a slab may land on either side, so a few pixels may differ.
                EXPECT_LE(pixels_apart(expected, **gpu, 2e-4f), expected.pixels.size() / 500)
                    << c.name << ", frame " << f;
            }
            history = **gpu;
        }
    }
}

// Dilation follows the nearer surface: with the box's depth nearer, a background pixel next to the
// box takes the box's motion; with the convention reversed, the box's pixels next to the
// background take the background's. Either way the outputs differ from the undilated ones.
TEST_F(ResolveGpu, DilationTakesTheNearestNeighborsMotionInEitherDepthConvention) {
    constexpr std::uint32_t w = 48, h = 32;
    const SceneFrames frames("asphalt", make_texture(TextureFamily::asphalt, w, h, 2), 12, true, false);
    for (bool larger : {false, true}) {
        ResolveOptions options;
        options.dilate_motion = true;
        options.depth_nearer_larger = larger;
        auto shader = resolve_shader("aabb", Mode::clip, options);
        ASSERT_TRUE(shader);
        auto resolve = make_resolve(*shader, w, h, options);
        ASSERT_TRUE(resolve);
        const CpuResolve cpu{options, unit_axes(*resolve_axis_set("aabb")), Mode::clip};
        const CpuResolve undilated{{}, cpu.axes, Mode::clip};
        Image history;
        std::size_t moved = 0;
        for (std::size_t f = 0; f < frames.frame_count(); ++f) {
            auto frame = frames.frame(f);
            ASSERT_TRUE(frame);
            auto gpu = resolve->advance(*frame, frames.starts_history(f));
            ASSERT_TRUE(gpu);
            if (f > 0) {
                EXPECT_LE(pixels_apart(cpu.frame(*frame, false, history), **gpu, 2e-4f), w * h / 500)
                    << "nearer larger " << larger << ", frame " << f;
                moved += pixels_apart(undilated.frame(*frame, false, history), **gpu, 1e-3f);
            }
            history = **gpu;
        }
        EXPECT_GT(moved, 0u) << "nearer larger " << larger << ": dilation changed nothing";
        // A frame without depth cannot be dilated: refused, not resolved with the pixel's own motion.
        auto frame = frames.frame(3);
        ASSERT_TRUE(frame);
        frame->depth.reset();
        auto refused = resolve->advance(*frame, false);
        ASSERT_FALSE(refused);
        EXPECT_NE(refused.error().message.find("this frame has no depth"), std::string::npos);
    }
}

TEST_F(ResolveGpu, AStillUnjitteredSequenceNeitherGhostsNorShimmers) {
    constexpr std::uint32_t w = 48, h = 32;
    const SceneFrames still("grass", make_texture(TextureFamily::grass, w, h, 2), 10, false, false);
    const HdrFlip flip(pixels_per_degree(ViewingConditions{}));
    for (const char* map : {"linear", "gamma:2"}) {
        ResolveOptions options;
        options.color_map = *parse_color_map(map);
        auto shader = resolve_shader("aabb", Mode::clip, options);
        ASSERT_TRUE(shader);
        auto resolve = make_resolve(*shader, w, h, options);
        ASSERT_TRUE(resolve);
        auto m = measure_sequence(*resolve, still, 2, *cpu_flip_evaluator(flip));
        ASSERT_TRUE(m) << m.error().message;
        if (options.color_map.kind == ColorMap::Kind::linear) {
            EXPECT_EQ(m->mean(kGhosting), 0.0);
            EXPECT_EQ(m->mean(kShimmer), 0.0);
        } else {
            // pow(pow(c, 2), 0.5) is c only to float rounding, which FLIP sees, barely.
            EXPECT_LT(m->mean(kGhosting), 1e-4) << map;
            EXPECT_LT(m->mean(kShimmer), 1e-4) << map;
        }
        EXPECT_EQ(m->frames, 8u);
        EXPECT_FALSE(m->against_reference);
    }
}

// `inner` with a camera cut at frame `cut`; with `hdr_scale`, its colors times that, measured as HDR.
class WithCut final : public FrameSource {
public:
    WithCut(const FrameSource& inner, std::size_t cut, float hdr_scale = 0)
        : inner_(inner), cut_(cut), hdr_scale_(hdr_scale) {}
    const std::string& name() const override { return inner_.name(); }
    std::uint32_t width() const override { return inner_.width(); }
    std::uint32_t height() const override { return inner_.height(); }
    std::size_t frame_count() const override { return inner_.frame_count(); }
    ColorRange color_range() const override { return hdr_scale_ > 0 ? ColorRange::hdr : inner_.color_range(); }
    bool starts_history(std::size_t i) const override { return i == cut_ || inner_.starts_history(i); }
    std::optional<glm::vec2> jitter(std::size_t i) const override { return inner_.jitter(i); }
    bool has_depth() const override { return inner_.has_depth(); }
    bool has_reference() const override { return inner_.has_reference(); }
    Result<LoadedFrame> frame(std::size_t i) const override {
        auto frame = inner_.frame(i);
        if (frame && hdr_scale_ > 0)
            for (glm::vec4& p : frame->color.pixels) p = glm::vec4(glm::vec3(p) * hdr_scale_, p.a);
        return frame;
    }
    std::string frame_label(std::size_t i) const override { return inner_.frame_label(i); }

private:
    const FrameSource& inner_;
    std::size_t cut_;
    float hdr_scale_;
};

TEST_F(ResolveGpu, ACameraCutDropsTheHistory) {
    constexpr std::uint32_t w = 48, h = 32;
    const SceneFrames moving("grass", make_texture(TextureFamily::grass, w, h, 5), 12, true, true);
    const WithCut cut(moving, 8);
    auto shader = resolve_shader("dop16-grass", Mode::clip, {});
    ASSERT_TRUE(shader);
    auto resolve = make_resolve(*shader, w, h, {});
    ASSERT_TRUE(resolve);
    for (std::size_t f = 0; f < cut.frame_count(); ++f) {
        auto frame = cut.frame(f);
        ASSERT_TRUE(frame);
        auto out = resolve->advance(*frame, cut.starts_history(f));
        ASSERT_TRUE(out);
        EXPECT_EQ(bit_identical(**out, frame->color), f == 0 || f == 8) << "frame " << f;
    }
    // In the sequence format the cut is a flag on the frame, and it lands in what kdop writes.
    const std::string json = sequence_json(cut);
    EXPECT_EQ(json.find("\"camera_cut\": true"), json.rfind("\"camera_cut\": true"));
    EXPECT_NE(json.find("\"camera_cut\": true"), std::string::npos) << json;
}

// Each shader's history stays on the device: two shaders resolved together, with their outputs read
// back only from frame 9 on, give bit for bit the frames of a resolve that reads every output
// back, across a camera cut; and a shader's history is its own, not the other's.
TEST_F(ResolveGpu, HistoriesKeptOnTheDeviceGiveTheFramesOfOneReadBackEveryFrame) {
    constexpr std::uint32_t w = 48, h = 32;
    const SceneFrames moving("grass", make_texture(TextureFamily::grass, w, h, 7), 14, true, true);
    const WithCut cut(moving, 6);
    auto box = resolve_shader("aabb", Mode::clip, {});
    auto dop = resolve_shader("dop32", Mode::clip, {});
    ASSERT_TRUE(box && dop);
    const Variant* both[] = {&box->variant(), &dop->variant()};
    auto together = TaaResolve::create(test::gpu(), both, w, h, {});
    ASSERT_TRUE(together) << together.error().message;
    std::vector<std::unique_ptr<TaaResolve>> alone;
    alone.push_back(make_resolve(*box, w, h, {}));
    alone.push_back(make_resolve(*dop, w, h, {}));
    ASSERT_TRUE(alone[0] && alone[1]);
    for (std::size_t f = 0; f < cut.frame_count(); ++f) {
        auto frame = cut.frame(f);
        ASSERT_TRUE(frame);
        const bool read = f >= 9;
        ASSERT_TRUE((*together)->advance_all(*frame, cut.starts_history(f), read));
        for (std::size_t s = 0; s < 2; ++s) {
            auto out = alone[s]->advance(*frame, cut.starts_history(f));
            ASSERT_TRUE(out);
            if (read) {
                EXPECT_TRUE(bit_identical((*together)->output(s), **out)) << "shader " << s << ", frame " << f;
            }
        }
        if (read) {
            EXPECT_FALSE(bit_identical((*together)->output(0), (*together)->output(1))) << "frame " << f;
        }
    }
}

// The one pass over a sequence with a camera cut, in LDR and in HDR (HDR-FLIP, its notes):
// every variant's figures are those of a pass of its own.
TEST_F(ResolveGpu, OnePassGivesEachVariantTheFiguresOfItsOwnPass) {
    constexpr std::uint32_t w = 48, h = 32;
    const SceneFrames moving("grass", make_texture(TextureFamily::grass, w, h, 6), 14, true, true);
    const HdrFlip flip(pixels_per_degree(ViewingConditions{}));
    std::vector<std::unique_ptr<RunnableVariant>> shaders;
    std::vector<const Variant*> variants;
    for (const char* set : {"aabb", "dop22", "ycocg"}) {
        shaders.push_back(resolve_shader(set, Mode::varclip, {}));
        ASSERT_TRUE(shaders.back());
        variants.push_back(&shaders.back()->variant());
    }
    for (float hdr_scale : {0.0f, 40.0f}) {
        const WithCut source(moving, 9, hdr_scale);
        auto all = TaaResolve::create(test::gpu(), variants, w, h, {});
        ASSERT_TRUE(all) << all.error().message;
        std::vector<std::size_t> outputs(variants.size());
        auto together = measure_sequence_all(
            **all, source, 3, *cpu_flip_evaluator(flip),
            [&](std::size_t s, std::size_t, const Image&) -> Result<void> { return ++outputs[s], Result<void>{}; });
        ASSERT_TRUE(together) << together.error().message;
        for (std::size_t s = 0; s < variants.size(); ++s) {
            EXPECT_EQ(outputs[s], source.frame_count() - 3);
            auto alone_resolve = make_resolve(*shaders[s], w, h, {});
            ASSERT_TRUE(alone_resolve);
            auto alone = measure_sequence(*alone_resolve, source, 3, *cpu_flip_evaluator(flip));
            ASSERT_TRUE(alone) << alone.error().message;
            const SequenceMeasurement& t = (*together)[s];
            EXPECT_EQ(t.range, hdr_scale > 0 ? ColorRange::hdr : ColorRange::ldr);
            EXPECT_EQ(t.mean(kGhosting), alone->mean(kGhosting)) << variants[s]->name << " x" << hdr_scale;
            EXPECT_EQ(t.mean(kShimmer), alone->mean(kShimmer)) << variants[s]->name << " x" << hdr_scale;
            EXPECT_EQ(t.frames, alone->frames);
            EXPECT_EQ(t.notes, alone->notes);
        }
    }
}

// Where an observer asks for maps, each measured frame carries every shader's FLIP map of the figure
// maps_show_ghosting names, the map that figure is the mean of: against the truth for a sequence
// measured for ghosting, against the shader's output before for one measured for shimmer alone, and
// none after a camera cut. In LDR and HDR, from the CPU's FLIP (equal to its map of the pair) and
// the device's (within DeviceFlip's 1e-5 per pixel).
TEST_F(ResolveGpu, MeasuredFramesCarryTheMapsTheirFiguresAreMeansOf) {
    constexpr std::uint32_t w = 48, h = 32;
    const SceneFrames moving("grass", make_texture(TextureFamily::grass, w, h, 8), 12, true, true);
    const double ppd = pixels_per_degree(ViewingConditions{});
    const HdrFlip flip(ppd);
    auto device = DeviceFlip::create(test::gpu(), ppd, w, h);
    ASSERT_TRUE(device) << device.error().message;
    auto box = resolve_shader("aabb", Mode::clip, {});
    auto dop = resolve_shader("dop32", Mode::clip, {});
    ASSERT_TRUE(box && dop);
    const Variant* both[] = {&box->variant(), &dop->variant()};
    constexpr std::size_t kCut = 7;
    for (float hdr_scale : {0.0f, 40.0f})
        for (const SequenceRoles roles : {SequenceRoles{}, SequenceRoles{.ghosting = false, .shimmer = true}})
            for (bool on_device : {false, true}) {
                const std::string what = fmt::format("x{} {} {}", hdr_scale, roles.ghosting ? "ghosting" : "shimmer",
                                                     on_device ? "device" : "cpu");
                const MeasuredFor source(std::make_shared<WithCut>(moving, kCut, hdr_scale), roles);
                auto resolve = TaaResolve::create(test::gpu(), both, w, h, {});
                ASSERT_TRUE(resolve) << resolve.error().message;
                std::vector<Image> before(2);
                std::size_t frames = 0;
                auto check = [&](const MeasuredFrame& frame) -> Result<void> {
                    ++frames;
                    EXPECT_EQ(frame.maps.size(), 2u) << what;
                    auto outputs = frame.outputs();
                    if (!outputs) return std::unexpected(outputs.error());
                    for (std::size_t s = 0; s < 2 && frame.maps.size() == 2; ++s) {
                        const Image& output = *(*outputs)[s];
                        const std::vector<float>& map = frame.maps[s];
                        const double figure =
                            roles.ghosting ? frame.figures[s].value(kGhosting) : frame.figures[s].value(kShimmer);
                        if (!roles.ghosting && frame.index == kCut) {
                            EXPECT_TRUE(map.empty()) << what << ": no output before a cut";
                        } else if (roles.ghosting || !before[s].pixels.empty()) { // frame 2's is not observed
                            const Image& against = roles.ghosting ? *frame.truth : before[s];
                            Result<std::vector<float>> expected = fail("not measured");
                            if (hdr_scale == 0)
                                expected = flip.ldr().error_map(against, output);
                            else if (auto maps = flip.maps(against, output, {}))
                                expected = std::move(maps->error);
                            if (!expected) return fail(what + ": " + expected.error().message);
                            EXPECT_EQ(map.size(), expected->size()) << what;
                            float worst = 0;
                            for (std::size_t i = 0; i < map.size() && i < expected->size(); ++i)
                                worst = std::max(worst, std::abs(map[i] - (*expected)[i]));
                            if (on_device) {
                                EXPECT_LE(worst, 1e-5f) << what << ", frame " << frame.index;
                            } else {
                                EXPECT_EQ(worst, 0.0f) << what << ", frame " << frame.index;
                                EXPECT_EQ(mean_error(map), figure) << what << ", frame " << frame.index;
                            }
                            // At the cut the output is the frame's color: no ghosting to map.
                            if (frame.index != kCut) {
                                EXPECT_GT(mean_error(map), 0.0) << what << ": a map of something";
                            }
                        }
                        before[s] = output;
                    }
                    return {};
                };
                auto mean = on_device ? device_flip_evaluator(**device) : cpu_flip_evaluator(flip);
                auto measured = measure_sequence_all(**resolve, source, 3, *mean, {}, {}, check, true);
                ASSERT_TRUE(measured) << what << ": " << measured.error().message;
                EXPECT_EQ(frames, source.frame_count() - 3);
                // Without maps asked for, none come.
                auto plain = TaaResolve::create(test::gpu(), both, w, h, {});
                ASSERT_TRUE(plain);
                ASSERT_TRUE(measure_sequence_all(**plain, source, 3, *mean, {}, {}, [&](const MeasuredFrame& frame) {
                    EXPECT_TRUE(frame.maps.empty());
                    return Result<void>{};
                }));
            }
}

// Measured on the device (DeviceFlip::load: each output checked, moved onto the range and
// measured where the resolve leaves it) every figure, output and map is bit for bit what the host
// path gives (outputs read back, within_range, uploaded to the same device FLIP), over a camera
// cut, for ghosting and shimmer together and each alone, maps asked for or not, in LDR and in HDR
// (each exposure range derived on the device where its image is there alone).
TEST_F(ResolveGpu, OutputsMeasuredOnTheDeviceGiveTheFiguresOfOutputsReadBack) {
    constexpr std::uint32_t w = 48, h = 32;
    const SceneFrames moving("grass", make_texture(TextureFamily::grass, w, h, 8), 12, true, true);
    const double ppd = pixels_per_degree(ViewingConditions{});
    auto device = DeviceFlip::create(test::gpu(), ppd, w, h);
    ASSERT_TRUE(device) << device.error().message;
    auto box = resolve_shader("aabb", Mode::clip, {});
    auto dop = resolve_shader("dop32", Mode::varclip, {});
    ASSERT_TRUE(box && dop);
    const Variant* both[] = {&box->variant(), &dop->variant()};
    auto on_device = device_flip_evaluator(**device);
    auto read_back = device_flip_evaluator(**device, {}, OutputPlacement::host); // the same FLIP, fed from the host
    struct Seen {
        std::vector<SequenceMeasurement> figures;
        std::vector<Image> outputs;
        std::vector<std::vector<float>> maps;
    };
    for (const float hdr_scale : {0.0f, 40.0f})
        for (const SequenceRoles roles : {SequenceRoles{}, SequenceRoles{.ghosting = true, .shimmer = false},
                                          SequenceRoles{.ghosting = false, .shimmer = true}})
            for (bool maps : {false, true}) {
                const std::string what = fmt::format("ghosting {}, shimmer {}, maps {}, HDR scale {}", roles.ghosting,
                                                     roles.shimmer, maps, hdr_scale);
                const MeasuredFor source(std::make_shared<WithCut>(moving, 7, hdr_scale), roles);
                auto measure = [&](FlipEvaluator& flip) {
                    Seen seen;
                    auto resolve = TaaResolve::create(test::gpu(), both, w, h, {});
                    EXPECT_TRUE(resolve);
                    if (!resolve) return seen;
                    auto observe = [&](const MeasuredFrame& frame) -> Result<void> {
                        auto outputs = frame.outputs();
                        if (!outputs) return std::unexpected(outputs.error());
                        for (const Image* output : *outputs) seen.outputs.push_back(*output);
                        for (const std::vector<float>& map : frame.maps) seen.maps.push_back(map);
                        return {};
                    };
                    auto measured = measure_sequence_all(**resolve, source, 3, flip, {}, {}, observe, maps);
                    EXPECT_TRUE(measured) << what << ": " << measured.error().message;
                    if (measured) seen.figures = std::move(*measured);
                    return seen;
                };
                const Seen host = measure(*read_back), here = measure(*on_device);
                ASSERT_EQ(here.figures.size(), 2u) << what;
                ASSERT_EQ(host.figures.size(), 2u) << what;
                for (std::size_t s = 0; s < 2; ++s) {
                    const SequenceMeasurement &a = here.figures[s], &b = host.figures[s];
                    EXPECT_TRUE(std::isnan(b.mean(kGhosting)) ? std::isnan(a.mean(kGhosting))
                                                              : a.mean(kGhosting) == b.mean(kGhosting))
                        << what;
                    EXPECT_TRUE(std::isnan(b.mean(kShimmer)) ? std::isnan(a.mean(kShimmer))
                                                             : a.mean(kShimmer) == b.mean(kShimmer))
                        << what;
                    ASSERT_EQ(a.per_frame.size(), b.per_frame.size()) << what;
                    for (std::size_t f = 0; f < a.per_frame.size(); ++f) {
                        const FrameFigures &x = a.per_frame[f], &y = b.per_frame[f];
                        EXPECT_TRUE(std::isnan(y.value(kGhosting)) ? std::isnan(x.value(kGhosting))
                                                                   : x.value(kGhosting) == y.value(kGhosting))
                            << what;
                        EXPECT_TRUE(std::isnan(y.value(kShimmer)) ? std::isnan(x.value(kShimmer))
                                                                  : x.value(kShimmer) == y.value(kShimmer))
                            << what;
                    }
                }
                EXPECT_GT(host.figures[0].per_frame.size(), 0u);
                ASSERT_EQ(here.outputs.size(), host.outputs.size()) << what;
                for (std::size_t o = 0; o < host.outputs.size(); ++o)
                    EXPECT_TRUE(bit_identical(here.outputs[o], host.outputs[o])) << what << ", output " << o;
                EXPECT_EQ(here.maps, host.maps) << what;
                EXPECT_EQ(host.maps.empty(), !maps) << what;
            }
}

// A history holding a linear ramp, sampled between texels: Catmull-Rom reproduces it exactly (up
// to float rounding) away from the edges, where clamping bends the ramp. The rectification keeps
// the history as it is, so the output shows the filter alone.
TEST_F(ResolveGpu, CatmullRomReproducesALinearRamp) {
    constexpr std::uint32_t w = 24, h = 16;
    ResolveOptions options;
    options.history_filter = HistoryFilter::catmull_rom;
    auto keep = build_taa_shader("#define KDOP_NEIGHBORS 9\n"
                                 "vec3 kdop_rectify(vec3 current, vec3 history, float gamma, vec3 n[9])\n"
                                 "{\n    return history;\n}\n",
                                 "taa-keep-history", options);
    ASSERT_TRUE(keep) << keep.error().message;
    auto resolve = make_resolve(**keep, w, h, options);
    ASSERT_TRUE(resolve);
    auto ramp = [](double x, double y) { return glm::dvec3(0.02 * x + 0.01 * y, 0.5 - 0.015 * x, 0.03 * y); };
    LoadedFrame first;
    first.color = Image(w, h);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) first.color.at(x, y) = glm::vec4(glm::vec3(ramp(x + 0.5, y + 0.5)), 1);
    ASSERT_TRUE(resolve->advance(first, true));
    LoadedFrame next;
    next.color = Image(w, h, glm::vec4(0.25f, 0.25f, 0.25f, 1));
    const glm::vec2 motion(0.3f, -0.45f);
    next.motion.assign(std::size_t(w) * h, motion);
    auto out = resolve->advance(next, false);
    ASSERT_TRUE(out);
    double worst = 0;
    for (std::uint32_t y = 3; y + 3 < h; ++y)
        for (std::uint32_t x = 3; x + 3 < w; ++x) {
            const glm::dvec3 history = ramp(x + 0.5 + motion.x, y + 0.5 + motion.y);
            const glm::dvec3 expected = history + 0.1 * (glm::dvec3(0.25) - history);
            worst = std::max(worst, glm::distance(expected, glm::dvec3(glm::vec3((*out)->at(x, y)))));
        }
    EXPECT_LT(worst, 2e-6);
}

// ---------------------------------------------------------------------------------------------
// Sequences on disk.

// Writes `source` as a sequence folder, as `kdop scene` does, with its motion files re-expressed
// in `convention`.
void write_sequence(const FrameSource& source, const fs::path& dir, const MotionConvention& convention) {
    for (const OutputWriter& writer :
         sequence_frame_writers(dir, std::shared_ptr<const FrameSource>(&source, [](const FrameSource*) {}))) {
        fs::create_directories(writer.path.parent_path());
        ASSERT_TRUE(writer.write(writer.path)) << writer.path;
    }
    std::string json = sequence_json(source);
    const bool uv = convention.units == MotionConvention::Units::uv;
    const bool current = convention.points_to == MotionConvention::PointsTo::current;
    const bool up = convention.y_axis == MotionConvention::YAxis::up;
    const std::string stated = fmt::format(R"("units": "{}",
  "points_to": "{}",
  "y_axis": "{}")",
                                           uv ? "uv" : "pixels", current ? "current" : "previous", up ? "up" : "down");
    const std::size_t at = json.find(R"("units")");
    json.replace(at, json.find('}', at) - at - 2, stated);
    test::write_file(dir / "sequence.json", json);
    // The motion files, in the convention: the inverse of canonical_motion().
    for (std::size_t i = 1; i < source.frame_count(); ++i) {
        const fs::path file = dir / fmt::format("motion/{:04}.exr", i);
        auto motion = read_data_image(file.string(), 2);
        ASSERT_TRUE(motion) << motion.error().message;
        for (glm::vec4& m : motion->pixels) {
            if (current) m = -m;
            if (up) m.y = -m.y;
            if (uv) m.x /= float(source.width()), m.y /= float(source.height());
        }
        const char* const xy[] = {"R", "G"};
        ASSERT_TRUE(write_atomically(
            {{file, [&](const fs::path& to) { return write_data_image_to(to, file.string(), *motion, xy); }}}));
    }
}

// 64x32: dividing by a power of two and multiplying back is exact, so uv motion loses nothing and
// the four conventions carry the same motion to the bit.
TEST_F(ResolveGpu, TheFourMotionConventionsGiveBitIdenticalOutputs) {
    constexpr std::uint32_t w = 64, h = 32;
    const SceneFrames moving("asphalt", make_texture(TextureFamily::asphalt, w, h, 4), 10, true, true);
    test::TempDir dir;
    using C = MotionConvention;
    const C conventions[] = {{C::Units::pixels, C::PointsTo::previous, C::YAxis::down},
                             {C::Units::uv, C::PointsTo::previous, C::YAxis::down},
                             {C::Units::pixels, C::PointsTo::current, C::YAxis::down},
                             {C::Units::pixels, C::PointsTo::previous, C::YAxis::up},
                             {C::Units::uv, C::PointsTo::current, C::YAxis::up}};
    auto shader = resolve_shader("dop22", Mode::clip, {});
    ASSERT_TRUE(shader);
    std::vector<Image> last;
    int n = 0;
    for (const C& c : conventions) {
        const fs::path folder = dir / fmt::format("s{}", n++);
        write_sequence(moving, folder, c);
        auto sequence = read_sequence(folder);
        ASSERT_TRUE(sequence) << sequence.error().message;
        const SequenceFrames frames(std::move(*sequence), InputSpace::from_file);
        auto resolve = make_resolve(*shader, w, h, {});
        ASSERT_TRUE(resolve);
        const Image* out = nullptr;
        for (std::size_t f = 0; f < frames.frame_count(); ++f) {
            auto frame = frames.frame(f);
            ASSERT_TRUE(frame) << frame.error().message;
            auto resolved = resolve->advance(*frame, frames.starts_history(f));
            ASSERT_TRUE(resolved);
            out = *resolved;
        }
        last.push_back(*out);
    }
    // And the same as resolving the frames in memory.
    auto resolve = make_resolve(*shader, w, h, {});
    ASSERT_TRUE(resolve);
    const Image* in_memory = nullptr;
    for (std::size_t f = 0; f < moving.frame_count(); ++f) in_memory = *resolve->advance(*moving.frame(f), f == 0);
    for (std::size_t i = 0; i < last.size(); ++i) EXPECT_TRUE(bit_identical(last[i], *in_memory)) << "convention " << i;
}

// ---------------------------------------------------------------------------------------------
// kdop scene, kdop taa --sequence

struct SequenceRun {
    test::TempDir dir;
    test::CommandResult kdop(const std::string& args) const { return test::run(test::kdop_binary() + " " + args); }
    // kdop's grass scene at 48x32, 8 frames, as the two sequences kdop taa measures.
    fs::path scenes() const {
        const fs::path out = dir / "scenes";
        auto r = kdop("scene --scenes grass --size 48x32 --frames 8 --out " + out.string());
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return out;
    }
};

// "shimmer,ghosting" of `variant`'s row on `scene` in a taa.csv.
std::string figures(const std::string& csv, const std::string& variant, const std::string& scene) {
    for (auto& row : test::csv_rows(csv))
        if (row["variant"] == variant && row["scene"] == scene) return row["shimmer"] + "," + row["ghosting"];
    return "no row for " + variant + " on " + scene;
}

// Runs kdop taa on `scene` in memory and on what `scenes` holds of it (kdop scene's two sequences),
// and expects the same figures: shimmer from <scene>-shimmer, ghosting from <scene>-ghosting.
void expect_replay_gives_the_in_memory_figures(const SequenceRun& t, const fs::path& scenes, const std::string& scene,
                                               const std::string& scene_args) {
    const std::string common = " --sets aabb dop22 --modes clip varclip --warmup 3 --timing-rounds 2 --no-charts";
    const fs::path memory_out = t.dir / (scene + "-memory"), replay_out = t.dir / (scene + "-replay");
    auto memory =
        t.kdop("taa --scenes " + scene + " --frames 5 " + scene_args + " --out " + memory_out.string() + common);
    ASSERT_EQ(memory.exit_code, 0) << memory.err;
    auto replay = t.kdop("taa --sequence " + (scenes / (scene + "-shimmer")).string() + " " +
                         (scenes / (scene + "-ghosting")).string() + " --out " + replay_out.string() + common);
    ASSERT_EQ(replay.exit_code, 0) << replay.err;
    const std::string in_memory = test::read_file(memory_out / "taa.csv");
    const std::string replayed = test::read_file(replay_out / "taa.csv");
    for (const char* variant : {"aabb-clip-n9", "dop22-clip-n9", "aabb-varclip-n9", "dop22-varclip-n9"}) {
        const std::string memory_figures = figures(in_memory, variant, scene);
        const std::string shimmer = memory_figures.substr(0, memory_figures.find(','));
        const std::string ghosting = memory_figures.substr(memory_figures.find(',') + 1);
        const std::string still = figures(replayed, variant, scene + "-shimmer");
        const std::string moving = figures(replayed, variant, scene + "-ghosting");
        EXPECT_EQ(still.substr(0, still.find(',')), shimmer) << variant << "\n" << replayed;
        EXPECT_EQ(moving.substr(moving.find(',') + 1), ghosting) << variant << "\n" << replayed;
    }
    const std::string report = test::read_file(replay_out / "report.md");
    EXPECT_NE(report.find(fmt::format("Sequences given with --sequence ({0}-shimmer, {0}-ghosting)", scene)),
              std::string::npos)
        << report;
}

TEST(CliSequence, ReplayingWhatKdopSceneWroteGivesTheInMemoryFigures) {
    SequenceRun t;
    const fs::path scenes = t.scenes();
    EXPECT_TRUE(fs::exists(scenes / "grass-shimmer" / "color" / "0007.exr"));
    EXPECT_TRUE(fs::exists(scenes / "grass-ghosting" / "motion" / "0007.exr"));
    EXPECT_FALSE(fs::exists(scenes / "grass-ghosting" / "motion" / "0000.exr")) << "the first frame has no history";
    expect_replay_gives_the_in_memory_figures(t, scenes, "grass", "--size 48x32");
}

// The same for a 3-D scene, its camera panning and its frames with references: kdop scene writes
// depth and references, and ghosting is measured against the references either way.
TEST(CliSequence, ReplayingA3dSceneGivesTheInMemoryFigures) {
    SequenceRun t;
    const fs::path scenes = t.dir / "scenes";
    const std::string scene_args = "--size 64x36 --camera pan --reference-samples 3";
    auto r = t.kdop("scene --scenes asphalt3d --frames 8 " + scene_args + " --out " + scenes.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* kind : {"color", "motion", "depth", "reference"})
        EXPECT_TRUE(fs::exists(scenes / "asphalt3d-ghosting" / kind / "0007.exr")) << kind;
    // Motion and depth keep only the channels they use: motion x and y, one depth.
    for (const auto& [kind, channels] :
         {std::pair{"motion", std::vector<std::string>{"R", "G"}}, std::pair{"depth", std::vector<std::string>{"Z"}},
          std::pair{"color", std::vector<std::string>{"R", "G", "B", "A"}}}) {
        auto in = OIIO::ImageInput::open((scenes / "asphalt3d-ghosting" / kind / "0007.exr").string());
        ASSERT_TRUE(in) << kind;
        EXPECT_EQ(in->spec().channelnames, channels) << kind;
        EXPECT_EQ(in->spec().format, OIIO::TypeDesc::FLOAT) << kind;
    }
    auto sequence = read_sequence(scenes / "asphalt3d-shimmer");
    ASSERT_TRUE(sequence) << sequence.error().message;
    ASSERT_TRUE(sequence->frames[3].jitter);
    EXPECT_EQ(*sequence->frames[3].jitter, r2_jitter(3));
    expect_replay_gives_the_in_memory_figures(t, scenes, "asphalt3d", scene_args);
    const std::string csv = test::read_file(t.dir / "asphalt3d-memory" / "taa.csv");
    EXPECT_NE(csv.find(",asphalt3d,"), std::string::npos) << csv;
    EXPECT_EQ(csv.find(",aliased,"), std::string::npos) << "against the references:\n" << csv;
}

// kdop scene --upscale 2 writes frames at half the size, their references at the full size and
// the output size in sequence.json; kdop taa replays them through the upscaling resolve and gives
// the figures it measures on the frames drawn in memory, to the digit.
TEST(CliSequence, ReplayingAnUpscaledSceneGivesTheInMemoryFigures) {
    SequenceRun t;
    const fs::path scenes = t.dir / "scenes";
    const std::string scene_args = "--size 64x36 --upscale 2 --reference-samples 4";
    auto r = t.kdop("scene --scenes grass3d --frames 8 " + scene_args + " --out " + scenes.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto sequence = read_sequence(scenes / "grass3d-ghosting");
    ASSERT_TRUE(sequence) << sequence.error().message;
    EXPECT_EQ(sequence->width, 32u);
    EXPECT_EQ(sequence->height, 18u);
    EXPECT_EQ(sequence->output_width, 64u);
    EXPECT_EQ(sequence->output_height, 36u);
    ASSERT_TRUE(sequence->frames[5].jitter);
    EXPECT_EQ(*sequence->frames[5].jitter, halton_jitter(5, 32)) << "every frame jittered, the moving one too";
    for (const auto& [kind, width] : {std::pair{"color", 32}, std::pair{"motion", 32}, std::pair{"reference", 64}}) {
        auto in = OIIO::ImageInput::open((scenes / "grass3d-ghosting" / kind / "0007.exr").string());
        ASSERT_TRUE(in) << kind;
        EXPECT_EQ(in->spec().width, width) << kind;
    }
    expect_replay_gives_the_in_memory_figures(t, scenes, "grass3d", scene_args);
    // The spatial-only upscale's row too.
    const std::string in_memory = test::read_file(t.dir / "grass3d-memory" / "taa.csv");
    const std::string replayed = test::read_file(t.dir / "grass3d-replay" / "taa.csv");
    auto ghosting = [](const std::string& figures) { return figures.substr(figures.find(',') + 1); };
    EXPECT_EQ(ghosting(figures(replayed, "spatial-lanczos2", "grass3d-ghosting")),
              ghosting(figures(in_memory, "spatial-lanczos2", "grass3d")))
        << replayed;
    for (const char* run : {"grass3d-memory", "grass3d-replay"})
        EXPECT_NE(test::read_file(t.dir / run / "report.md").find("upscaling with the lanczos2 filter"),
                  std::string::npos)
            << run;

    // A reference of the frames' size in an upscaled sequence is refused, naming it.
    const fs::path reference = scenes / "grass3d-ghosting" / "reference" / "0004.exr";
    fs::copy_file(scenes / "grass3d-ghosting" / "color" / "0004.exr", reference, fs::copy_options::overwrite_existing);
    auto refused = t.kdop("taa --sequence " + (scenes / "grass3d-ghosting").string() +
                          " --warmup 3 --sets aabb "
                          "--modes clip --no-charts --out " +
                          (t.dir / "refused").string());
    EXPECT_EQ(refused.exit_code, 1);
    EXPECT_NE(refused.err.find("0004.exr: 32x18, but the sequence's output is 64x36"), std::string::npos)
        << refused.err;
}

// An upscaled sequence beside a native one: kdop taa puts the spatial-only upscale (the same
// filter, no history) after the variants on the upscaled one only, untimed, with the ratio in
// taa.csv's upscale column; report.html's viewer offers it only there. An engine choice of the
// clip's samples (UE4's sample distance) changes the variants' figures and not the spatial row's,
// which never clips; the spatial row replays from the files as in memory.
TEST(CliSequence, AnUpscaledSequenceHasASpatialOnlyRowBesideItsVariants) {
    SequenceRun t;
    const fs::path scenes = t.dir / "upscaled", native = t.scenes();
    const std::string scene_args = "--size 64x36 --upscale 2 --reference-samples 4";
    ASSERT_EQ(t.kdop("scene --scenes grass3d --frames 8 " + scene_args + " --out " + scenes.string()).exit_code, 0);
    const std::string sources =
        " --sequence " + (scenes / "grass3d-ghosting").string() + " " + (native / "grass-ghosting").string();
    const std::string common = " --sets aabb dop22 --modes clip --warmup 3 --timing-rounds 2 --no-charts";
    const fs::path out = t.dir / "taa", ue4 = t.dir / "taa-ue4";
    auto r = t.kdop("taa" + sources + common + " --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto r2 = t.kdop("taa" + sources + common + " --upscale-sample-distance ue4 --out " + ue4.string());
    ASSERT_EQ(r2.exit_code, 0) << r2.err;

    const std::string csv = test::read_file(out / "taa.csv");
    std::map<std::string, std::vector<std::string>> variants; // by scene, in order
    for (auto& row : test::csv_rows(csv)) {
        variants[row["scene"]].push_back(row["variant"]);
        EXPECT_EQ(row["upscale"], row["scene"] == "grass3d-ghosting" ? "2" : "1") << row["variant"];
        EXPECT_EQ(row["ms"].empty(), row["variant"] == "spatial-lanczos2") << row["variant"];
    }
    EXPECT_EQ(variants["grass3d-ghosting"],
              (std::vector<std::string>{"aabb-clip-n9", "dop22-clip-n9", "spatial-lanczos2"}));
    EXPECT_EQ(variants["grass-ghosting"], (std::vector<std::string>{"aabb-clip-n9", "dop22-clip-n9"}));

    // What the history buys: the spatial upscale ghosts more than every clip.
    const auto ghosting = [](const std::string& figures) { return std::stod(figures.substr(figures.find(',') + 1)); };
    const double spatial = ghosting(figures(csv, "spatial-lanczos2", "grass3d-ghosting"));
    for (const char* variant : {"aabb-clip-n9", "dop22-clip-n9"})
        EXPECT_GT(spatial, ghosting(figures(csv, variant, "grass3d-ghosting"))) << variant << "\n" << csv;

    const std::string with_ue4 = test::read_file(ue4 / "taa.csv");
    EXPECT_EQ(figures(with_ue4, "spatial-lanczos2", "grass3d-ghosting"),
              figures(csv, "spatial-lanczos2", "grass3d-ghosting"));
    EXPECT_NE(figures(with_ue4, "dop22-clip-n9", "grass3d-ghosting"),
              figures(csv, "dop22-clip-n9", "grass3d-ghosting"));
    EXPECT_EQ(figures(with_ue4, "dop22-clip-n9", "grass-ghosting"), figures(csv, "dop22-clip-n9", "grass-ghosting"))
        << "a sequence that does not upscale ignores the upscaling options";
    EXPECT_NE(test::read_file(ue4 / "report.md").find("UE4's distance"), std::string::npos);

    // The viewer: the run's three variants, two of them for the native sequence.
    const std::string html = test::read_file(out / "report.html");
    EXPECT_NE(html.find(R"("variants":["aabb-clip-n9","dop22-clip-n9","spatial-lanczos2"])"), std::string::npos);
    EXPECT_NE(html.find(R"("name":"grass-ghosting")"), std::string::npos);
    const std::size_t native_entry = html.find(R"("name":"grass-ghosting")");
    EXPECT_NE(html.find(R"("variants":2)", native_entry), std::string::npos) << html.substr(native_entry, 400);
    EXPECT_TRUE(fs::exists(out / "viewer" / "grass3d-ghosting" / "grass3d-ghosting"));
}

// kdop scene writes what each of its sequences is for; kdop taa measures only that, and leaves the
// other figure out everywhere it writes one.
TEST(CliSequence, ASequenceMeantForOneFigureHasNoOtherAnywhere) {
    SequenceRun t;
    const fs::path scenes = t.scenes();
    auto moving = read_sequence(scenes / "grass-ghosting");
    ASSERT_TRUE(moving) << moving.error().message;
    EXPECT_EQ(moving->measure, (SequenceRoles{.ghosting = true, .shimmer = false}));
    auto still = read_sequence(scenes / "grass-shimmer");
    ASSERT_TRUE(still) << still.error().message;
    EXPECT_EQ(still->measure, (SequenceRoles{.ghosting = false, .shimmer = true}));

    const fs::path out = t.dir / "taa";
    auto r =
        t.kdop("taa --sequence " + (scenes / "grass-ghosting").string() + " " + (scenes / "grass-shimmer").string() +
               " --sets aabb dop22 --modes clip --warmup 3 "
               "--timing-rounds 2 --write-frames --out " +
               out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto rows = test::csv_rows(test::read_file(out / "taa.csv"));
    ASSERT_EQ(rows.size(), 4u);

    // The moving sequence's picture shows the frame where the variants' ghosting differs most (the
    // earliest of equals), its outputs those the pass wrote of that frame; the still one has none.
    std::map<std::string, std::pair<double, double>> by_frame; // frame: lowest and highest ghosting
    for (auto f : test::csv_rows(test::read_file(out / "taa_frames.csv")))
        if (f["sequence"] == "grass-ghosting") {
            auto [it, first] = by_frame.try_emplace(f["frame"], INFINITY, -INFINITY);
            it->second = {std::min(it->second.first, std::stod(f["ghosting"])),
                          std::max(it->second.second, std::stod(f["ghosting"]))};
        }
    int chosen = -1;
    double widest = -1;
    for (int frame = 3; frame < 8; ++frame) {
        const auto [low, high] = by_frame.at(std::to_string(frame));
        if (high - low > widest) widest = high - low, chosen = frame;
    }
    EXPECT_TRUE(fs::exists(out / "ghosting-grass-ghosting.png"));
    EXPECT_FALSE(fs::exists(out / "ghosting-grass-shimmer.png")) << "nothing to ghost";
    for (const char* variant : {"aabb-clip-n9", "dop22-clip-n9"}) {
        auto shown = read_image((out / "frames" / "grass-ghosting" / (std::string(variant) + ".exr")).string());
        auto written =
            read_image((out / "frames" / "grass-ghosting" / variant / fmt::format("{:04}.exr", chosen)).string());
        ASSERT_TRUE(shown && written) << variant;
        EXPECT_TRUE(bit_identical(*shown, *written)) << variant << ", frame " << chosen;
    }
    EXPECT_NE(test::read_file(out / "report.md").find("The frame where the variants' ghosting differs most"),
              std::string::npos);
    for (auto row : rows) {
        const bool ghosting = row["scene"] == "grass-ghosting";
        for (const char* figure : {"shimmer", "shimmer_median", "shimmer_p95", "worst_shimmer_frame"})
            EXPECT_EQ(row[figure].empty(), ghosting) << row["scene"] << " " << figure;
        for (const char* figure :
             {"ghosting", "ghosting_median", "ghosting_p95", "worst_ghosting_frame", "ghosting_against"})
            EXPECT_EQ(row[figure].empty(), !ghosting) << row["scene"] << " " << figure;
    }
    for (auto row : test::csv_rows(test::read_file(out / "taa_frames.csv"))) {
        EXPECT_EQ(row["ghosting"].empty(), row["sequence"] == "grass-shimmer") << row["sequence"] << row["frame"];
        if (row["sequence"] == "grass-ghosting") {
            EXPECT_TRUE(row["shimmer"].empty()) << row["frame"];
        }
    }
    const auto json = nlohmann::json::parse(test::read_file(out / "taa.json"));
    for (const auto& row : json["rows"]) {
        const bool ghosting = row["scene"] == "grass-ghosting";
        EXPECT_EQ(row["shimmer"].is_null(), ghosting) << row;
        EXPECT_EQ(row["ghosting"].is_null(), !ghosting) << row;
    }
    const std::string report = test::read_file(out / "report.md");
    EXPECT_NE(report.find("A figure shown as – is not measured: one the sequence is not meant for"), std::string::npos)
        << report;
    EXPECT_NE(report.find("Least shimmer first."), std::string::npos) << report;
    for (const char* chart :
         {"trade-grass-ghosting.png", "over-time-grass-ghosting.png", "over-time-grass-shimmer.png"})
        EXPECT_TRUE(fs::exists(out / chart)) << chart;
    EXPECT_NE(report.find("(over-time-grass-shimmer.png)"), std::string::npos) << report;

    // A sequence.json that says something else about its figures is refused, naming the key.
    const std::string written = test::read_file(scenes / "grass-shimmer" / "sequence.json");
    for (const char* wrong : {R"("ghosting")", "[]", R"(["ghosting", "ghosting"])", R"(["blur"])", "[1]"}) {
        std::string text = written;
        const std::size_t at = text.find(R"("measure")");
        ASSERT_NE(at, std::string::npos);
        const std::size_t end = text.find(']', at);
        text.replace(at, end + 1 - at, std::string(R"("measure": )") + wrong);
        test::write_file(scenes / "grass-shimmer" / "sequence.json", text);
        auto refused = read_sequence(scenes / "grass-shimmer");
        ASSERT_FALSE(refused) << wrong;
        EXPECT_NE(refused.error().message.find("sequence.json: measure:"), std::string::npos)
            << refused.error().message;
    }
}

// taa_frames.csv holds every measured frame's figures: their means are taa.csv's, to the last
// bit, and the medians, 95th percentiles and worst frames are theirs.
TEST(CliSequence, PerFrameFiguresGiveTheTablesMeansAndPercentiles) {
    SequenceRun t;
    const fs::path scenes = t.scenes();
    const fs::path out = t.dir / "taa";
    // Under a name of its own: the scene's own frames are grass-ghosting.
    fs::rename(scenes / "grass-ghosting", scenes / "captured");
    auto r =
        t.kdop("taa --scenes grass --size 48x32 --frames 6 --warmup 3 --sequence " + (scenes / "captured").string() +
               " --sets aabb dop22 --modes clip varclip --timing-rounds 2 --no-charts --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto frames = test::csv_rows(test::read_file(out / "taa_frames.csv"));
    const auto rows = test::csv_rows(test::read_file(out / "taa.csv"));
    ASSERT_EQ(rows.size(), 8u); // 4 variants x the scene and the sequence
    // numpy.quantile's default (linear), written out here apart from harness/statistics.h.
    auto numpy_quantile = [](std::vector<double> v, double q) {
        std::sort(v.begin(), v.end());
        const double h = (double(v.size()) - 1) * q;
        const double lower = v[std::size_t(std::floor(h))], upper = v[std::size_t(std::ceil(h))];
        return lower + (h - std::floor(h)) * (upper - lower);
    };
    for (auto row : rows) {
        for (const std::string figure : {"ghosting", "shimmer"}) {
            std::vector<double> values;
            std::string worst;
            double largest = -1;
            for (auto f : frames)
                if (f["variant"] == row["variant"] && f["scene"] == row["scene"] && !f[figure].empty()) {
                    values.push_back(std::stod(f[figure]));
                    if (values.back() > largest)
                        largest = values.back(), worst = f["sequence"] + " frame " + f["frame"];
                }
            SCOPED_TRACE(row["variant"] + " on " + row["scene"] + ", " + figure);
            if (row[figure].empty()) {
                EXPECT_TRUE(values.empty());
                continue;
            }
            ASSERT_FALSE(values.empty());
            double sum = 0;
            for (double v : values) sum += v;
            EXPECT_EQ(sum / double(values.size()), std::stod(row[figure])) << "the mean, exactly";
            EXPECT_DOUBLE_EQ(numpy_quantile(values, 0.5), std::stod(row[figure + "_median"]));
            EXPECT_DOUBLE_EQ(numpy_quantile(values, 0.95), std::stod(row[figure + "_p95"]));
            EXPECT_EQ(row["worst_" + figure + "_frame"], worst);
        }
    }
    // The scene's row comes from its two sequences, 6 measured frames each: shimmer from the still
    // one, ghosting from the moving one.
    std::size_t scene_frames = 0;
    for (auto f : frames) scene_frames += f["variant"] == "aabb-clip-n9" && f["scene"] == "grass";
    EXPECT_EQ(scene_frames, 12u);
    const std::string report = test::read_file(out / "report.md");
    EXPECT_NE(report.find("Each variant's worst frames:"), std::string::npos) << report;
}

TEST(CliSequence, WritesEveryMeasuredFrameAndMeasuresAgainstReferences) {
    SequenceRun t;
    const fs::path scenes = t.scenes();
    // The moving sequence with its own color as every frame's reference: the same figures as
    // against the aliased frame, now labeled as measured against a reference.
    const fs::path moving = scenes / "grass-ghosting";
    std::string json = test::read_file(moving / "sequence.json");
    for (std::size_t at = 0; (at = json.find("\"color\": \"color/", at)) != std::string::npos; at += 10) {
        const std::string file = json.substr(at + 10, json.find('"', at + 10) - at - 10);
        json.insert(at, "\"reference\": \"" + file + "\", ");
        at += file.size() + 17;
    }
    test::write_file(moving / "sequence.json", json);
    const fs::path out = t.dir / "taa";
    auto r = t.kdop("taa --sequence " + moving.string() +
                    " --sets aabb --modes clip --warmup 3 --timing-rounds 2 "
                    "--no-charts --write-frames --out " +
                    out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string csv = test::read_file(out / "taa.csv");
    EXPECT_NE(csv.find(",grass-ghosting,"), std::string::npos) << csv;
    EXPECT_NE(csv.find(",reference,LDR-FLIP\n"), std::string::npos) << csv;
    for (int f = 0; f < 8; ++f)
        EXPECT_EQ(fs::exists(out / "frames" / "grass-ghosting" / "aabb-clip-n9" / fmt::format("{:04}.exr", f)), f >= 3)
            << "frame " << f;
    auto last = read_image((out / "frames" / "grass-ghosting" / "aabb-clip-n9" / "0007.exr").string());
    ASSERT_TRUE(last) << last.error().message;
    EXPECT_EQ(last->width, 48u);
}

// `dir`'s sequence.json with `from` replaced by `to`.
void replace_in_json(const fs::path& dir, const std::string& from, const std::string& to) {
    std::string json = test::read_file(dir / "sequence.json");
    ASSERT_NE(json.find(from), std::string::npos) << from;
    json.replace(json.find(from), from.size(), to);
    test::write_file(dir / "sequence.json", json);
}

// `dir`'s sequence.json without its "measure": a capture meant for both figures, as a renderer's is.
void measure_both(const fs::path& dir) {
    std::string json = test::read_file(dir / "sequence.json");
    const std::size_t at = json.find("\"measure\"");
    ASSERT_NE(at, std::string::npos);
    json.erase(at, json.find("],", at) + 2 - at);
    test::write_file(dir / "sequence.json", json);
}

// A number of a row of taa.csv, as written (every digit).
double figure(const std::string& csv, const std::string& variant, const std::string& scene, bool ghosting) {
    const std::string both = figures(csv, variant, scene);
    return std::stod(ghosting ? both.substr(both.find(',') + 1) : both.substr(0, both.find(',')));
}

// The moving grass scene made HDR: every color times 6 and a highlight of 40 moving along row 5,
// in a sequence that says so ("color": {"range": "hdr"}). Measured in HDR-FLIP on the device, its
// ghosting is the CPU's HDR-FLIP of each written output against its frame, and --cpu-flip gives
// the device's figures (within DeviceFlip's 1e-6 relative); exposures set on the command line are
// the ones used.
TEST(CliSequence, AnHdrSequenceIsMeasuredInHdrFlip) {
    SequenceRun t;
    const fs::path hdr = t.scenes() / "grass-ghosting";
    for (int f = 0; f < 8; ++f) {
        const std::string file = (hdr / "color" / fmt::format("{:04}.exr", f)).string();
        auto color = read_image(file);
        ASSERT_TRUE(color) << color.error().message;
        for (glm::vec4& p : color->pixels) p = glm::vec4(glm::vec3(p) * 6.0f, 1.0f);
        color->at(4 + 3 * f, 5) = glm::vec4(40.0f, 36.0f, 30.0f, 1.0f);
        ASSERT_TRUE(write_image(file, *color));
    }
    replace_in_json(hdr, R"("range": "ldr")", R"("range": "hdr")");
    measure_both(hdr);
    const std::string common = " --sets aabb dop32 --modes clip --warmup 3 --timing-rounds 2 --no-charts";
    const fs::path device = t.dir / "device", cpu = t.dir / "cpu";
    auto r = t.kdop("taa --sequence " + hdr.string() + common + " --write-frames --out " + device.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto c = t.kdop("taa --sequence " + hdr.string() + common + " --cpu-flip --out " + cpu.string());
    ASSERT_EQ(c.exit_code, 0) << c.err;
    const std::string csv = test::read_file(device / "taa.csv"), cpu_csv = test::read_file(cpu / "taa.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3) << csv;
    EXPECT_EQ(csv.find(",LDR-FLIP"), std::string::npos) << csv;
    EXPECT_NE(csv.find(",aliased,HDR-FLIP\n"), std::string::npos) << csv;
    EXPECT_NE(test::read_file(device / "report.md").find("measured in HDR-FLIP instead"), std::string::npos);
    // Its ghosting picture: the frames as measured (EXR, above 1) and tone mapped to look at (PNG),
    // labeled as HDR-FLIP's; the viewer's frames and maps in HDR-FLIP too.
    EXPECT_TRUE(fs::exists(device / "ghosting-grass-ghosting.png"));
    auto shown = read_image((device / "frames" / "grass-ghosting" / "aabb-clip-n9.exr").string());
    auto looked_at = read_image((device / "frames" / "grass-ghosting" / "aabb-clip-n9.png").string());
    ASSERT_TRUE(shown && looked_at);
    float brightest = 0, brightest_png = 0;
    for (const glm::vec4& p : shown->pixels) brightest = std::max(brightest, p.r);
    for (const glm::vec4& p : looked_at->pixels) brightest_png = std::max(brightest_png, p.r);
    EXPECT_GT(brightest, 1.5f);
    EXPECT_LE(brightest_png, 1.0f);
    EXPECT_GT(brightest_png, 0.5f);
    EXPECT_NE(test::read_file(device / "report.html").find("HDR-FLIP against the aliased frame"), std::string::npos);
    EXPECT_TRUE(fs::exists(device / "viewer" / "grass-ghosting" / "grass-ghosting"));

    const HdrFlip flip(pixels_per_degree(ViewingConditions{}));
    for (const char* variant : {"aabb-clip-n9", "dop32-clip-n9"}) {
        double sum = 0;
        for (int f = 3; f < 8; ++f) {
            auto color = read_image((hdr / "color" / fmt::format("{:04}.exr", f)).string());
            auto output =
                read_image((device / "frames" / "grass-ghosting" / variant / fmt::format("{:04}.exr", f)).string());
            ASSERT_TRUE(color && output) << variant << " frame " << f;
            auto maps = flip.maps(*color, *output, {});
            ASSERT_TRUE(maps) << maps.error().message;
            sum += maps->mean;
        }
        const double ghosting = figure(csv, variant, "grass-ghosting", true);
        EXPECT_GT(ghosting, 0.0) << variant;
        EXPECT_NEAR(ghosting, sum / 5, 1e-6 * ghosting) << variant;
        EXPECT_NEAR(figure(cpu_csv, variant, "grass-ghosting", true), ghosting, 1e-6 * ghosting) << variant;
        const double shimmer = figure(csv, variant, "grass-ghosting", false);
        EXPECT_GT(shimmer, 0.0) << variant;
        EXPECT_NEAR(figure(cpu_csv, variant, "grass-ghosting", false), shimmer, 1e-6 * shimmer) << variant;
    }

    // Exposures from the command line: the CPU's HDR-FLIP at those.
    const fs::path given = t.dir / "given";
    auto g = t.kdop("taa --sequence " + hdr.string() + common +
                    " --tone-mapper hable --start-exposure -3 --stop-exposure 1 --exposures 3 --write-frames --out " +
                    given.string());
    ASSERT_EQ(g.exit_code, 0) << g.err;
    double sum = 0;
    for (int f = 3; f < 8; ++f) {
        auto color = read_image((hdr / "color" / fmt::format("{:04}.exr", f)).string());
        auto output =
            read_image((given / "frames" / "grass-ghosting" / "aabb-clip-n9" / fmt::format("{:04}.exr", f)).string());
        ASSERT_TRUE(color && output);
        auto maps = flip.maps(*color, *output, {ToneMapper::hable, -3.0f, 1.0f, 3});
        ASSERT_TRUE(maps) << maps.error().message;
        sum += maps->mean;
    }
    const double ghosting = figure(test::read_file(given / "taa.csv"), "aabb-clip-n9", "grass-ghosting", true);
    EXPECT_NEAR(ghosting, sum / 5, 1e-6 * ghosting);
    EXPECT_NE(test::read_file(given / "report.md").find("hable tone mapper, 3 exposures from -3 to 1"),
              std::string::npos);

    // The same frames in a sequence that does not say it is HDR are refused, pointing at the key;
    // a negative value in an HDR one is refused; HDR-FLIP's options without an HDR sequence are a
    // wrong command line. Nothing is written.
    replace_in_json(hdr, R"("range": "hdr")", R"("range": "ldr")");
    auto ldr = t.kdop("taa --sequence " + hdr.string() + common + " --out " + (t.dir / "out").string());
    EXPECT_EQ(ldr.exit_code, 1);
    EXPECT_NE(ldr.err.find(R"(0000.exr (frame 0): color pixel ()"), std::string::npos) << ldr.err;
    EXPECT_NE(ldr.err.find(R"(outside [0, 1]; this sequence is measured in LDR-FLIP)"), std::string::npos) << ldr.err;
    EXPECT_NE(ldr.err.find(R"("color": {"range": "hdr"})"), std::string::npos) << ldr.err;
    auto options =
        t.kdop("taa --sequence " + hdr.string() + common + " --tone-mapper hable --out " + (t.dir / "out").string());
    EXPECT_EQ(options.exit_code, 2);
    EXPECT_NE(options.err.find("--tone-mapper: only HDR sequences"), std::string::npos) << options.err;
    replace_in_json(hdr, R"("range": "ldr")", R"("range": "hdr")");
    Image negative(48, 32, glm::vec4(0.5f, 0.5f, 0.5f, 1));
    negative.at(9, 2).g = -0.5f;
    ASSERT_TRUE(write_image((hdr / "color" / "0004.exr").string(), negative));
    auto below = t.kdop("taa --sequence " + hdr.string() + common + " --out " + (t.dir / "out").string());
    EXPECT_EQ(below.exit_code, 1);
    EXPECT_NE(below.err.find("0004.exr (frame 4): color pixel (9, 2) has G -0.5; HDR-FLIP takes finite linear "
                             "values from 0 up"),
              std::string::npos)
        << below.err;
    EXPECT_FALSE(fs::exists(t.dir / "out"));
}

TEST(CliSequence, RefusesBadSequencesNamingTheFileAndWritesNothing) {
    SequenceRun t;
    const fs::path scenes = t.scenes();
    const fs::path good = scenes / "grass-ghosting";
    // Each case: a copy of the good sequence, spoiled.
    int n = 0;
    auto spoiled = [&](const std::function<void(const fs::path&)>& spoil) {
        const fs::path copy = t.dir / fmt::format("bad{}", n++);
        fs::copy(good, copy, fs::copy_options::recursive);
        spoil(copy);
        return copy;
    };
    const struct {
        fs::path sequence;
        std::string message;
    } cases[] = {
        {spoiled([](const fs::path& d) { fs::remove(d / "color" / "0005.exr"); }), "color/0005.exr"},
        {spoiled(
             [](const fs::path& d) { ASSERT_TRUE(write_image((d / "color" / "0006.exr").string(), Image(10, 10))); }),
         "0006.exr: 10x10, but the sequence is 48x32"},
        {spoiled([](const fs::path& d) {
             Image motion(48, 32, glm::vec4(0));
             motion.at(5, 4).x = NAN;
             ASSERT_TRUE(write_image((d / "motion" / "0004.exr").string(), motion));
         }),
         "motion/0004.exr: pixel (5, 4) holds nan in channel 0; motion must be finite"},
        {spoiled([](const fs::path& d) {
             Image hdr(48, 32, glm::vec4(0.5f, 0.5f, 0.5f, 1));
             hdr.at(7, 2).g = 3.5f;
             ASSERT_TRUE(write_image((d / "color" / "0004.exr").string(), hdr));
         }),
         "color/0004.exr (frame 4): color pixel (7, 2) has G 3.5, outside [0, 1]"},
        {spoiled([&](const fs::path& d) { replace_in_json(d, "\"previous\"", "\"next\""); }),
         "motion.points_to: \"next\" is not a convention kdop knows"},
        {spoiled([&](const fs::path& d) { replace_in_json(d, "\"width\": 48,", "\"width\": 48"); }),
         "sequence.json:4:"},
    };
    for (const auto& c : cases) {
        const fs::path out = t.dir / "out";
        auto r = t.kdop("taa --sequence " + c.sequence.string() +
                        " --sets aabb --modes clip --warmup 3 "
                        "--timing-rounds 2 --no-charts --write-frames --out " +
                        out.string());
        EXPECT_EQ(r.exit_code, 1) << c.message << "\n" << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out)) << c.message;
    }
    // Options: a sequence too short for the warmup (the command line's --warmup: exit 2), a bad color map.
    auto short_run = t.kdop("taa --sequence " + good.string() + " --warmup 8 --out " + (t.dir / "out").string());
    EXPECT_EQ(short_run.exit_code, 2);
    EXPECT_NE(short_run.err.find("--sequence: " + good.string() + ": 8 frames, and --warmup 8 leaves none to measure"),
              std::string::npos)
        << short_run.err;
    auto bad_map = t.kdop("taa --sequence " + good.string() + " --color-map gamma:0 --out " + (t.dir / "out").string());
    EXPECT_EQ(bad_map.exit_code, 2);
    EXPECT_NE(bad_map.err.find("gamma:G must be a number from 0.01 to 100"), std::string::npos) << bad_map.err;
    EXPECT_FALSE(fs::exists(t.dir / "out"));
}

} // namespace
} // namespace kdop
