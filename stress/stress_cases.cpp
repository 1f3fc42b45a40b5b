#include "stress/stress_cases.h"

#include "generator/scaled_axis.h"
#include "images/random.h"

#include <glm/common.hpp>
#include <glm/gtc/packing.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <limits>

namespace kdop {
namespace {

using Colors = std::array<glm::vec3, 9>; // a 3x3 tile, row-major; [4] is the center pixel

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kFloatMax = std::numeric_limits<float>::max();
constexpr float kHalfMax = 65504.0f;
constexpr int kTilesPerRow = 8;

glm::vec3 center(const Colors& c) { return c[4]; }

Colors flat(glm::vec3 color) {
    Colors c;
    c.fill(color);
    return c;
}

// Channels uniform in [lo, hi].
Colors random_colors(Random& random, double lo, double hi) {
    Colors c;
    for (glm::vec3& color : c)
        for (int ch = 0; ch < 3; ++ch) color[ch] = static_cast<float>(random.uniform(lo, hi));
    return c;
}

// Grays g * (1, 1, 1): a neighborhood on a line, flat in two dimensions of color.
Colors gray_line(Random& random, double hi) {
    Colors c;
    for (glm::vec3& color : c) color = glm::vec3(static_cast<float>(random.uniform(0, hi)));
    return c;
}

class CaseBuilder {
public:
    CaseBuilder(std::string name, std::string description, TextureFormat format = TextureFormat::rgba32f)
        : case_{std::move(name), std::move(description), format, {}, {}} {}

    void add(const Colors& colors, glm::vec3 history) { tiles_.push_back({colors, history}); }

    // Histories every neighborhood is tried with: the pixel's own color, a corner neighbor, the
    // mean (inside), twice as far as a neighbor (outside), far out in a random direction, and a
    // hair off the pixel's color (on a slab when the neighborhood is flat).
    void add_usual_histories(const Colors& colors, Random& random) {
        const glm::vec3 current = center(colors);
        glm::vec3 mean(0), lo(INFINITY), hi(-INFINITY);
        int finite = 0;
        for (const glm::vec3& c : colors) {
            if (!std::isfinite(c.x + c.y + c.z)) continue; // a poisoned neighbor must not poison the histories
            ++finite;
            mean += c;
            lo = glm::min(lo, c);
            hi = glm::max(hi, c);
        }
        mean /= float(finite);
        const glm::vec3 size = glm::max(glm::abs(lo), glm::abs(hi));
        const float scale = std::max({size.x, size.y, size.z, 1e-30f});
        glm::vec3 direction;
        for (int ch = 0; ch < 3; ++ch) direction[ch] = static_cast<float>(random.uniform(-1, 1));
        add(colors, current);
        add(colors, colors[0]);
        add(colors, mean);
        add(colors, current + 2.0f * (colors[8] - current));
        add(colors, current + direction * (3.0f * glm::length(hi - lo) + 0.5f * scale));
        add(colors, current + glm::vec3(1.0f, -1.0f, 0.5f) * (1e-6f * scale));
    }

    // Every pixel's history is its own color (not just the tile center's).
    void history_is_current() { history_is_current_ = true; }

    StressCase finish() && {
        const std::uint32_t rows = static_cast<std::uint32_t>((tiles_.size() + kTilesPerRow - 1) / kTilesPerRow);
        case_.current = Image(3 * kTilesPerRow, 3 * rows);
        case_.history = Image(3 * kTilesPerRow, 3 * rows);
        for (std::size_t i = 0; i < tiles_.size(); ++i) {
            const std::uint32_t x0 = 3 * static_cast<std::uint32_t>(i % kTilesPerRow);
            const std::uint32_t y0 = 3 * static_cast<std::uint32_t>(i / kTilesPerRow);
            for (std::uint32_t y = 0; y < 3; ++y)
                for (std::uint32_t x = 0; x < 3; ++x) {
                    case_.current.at(x0 + x, y0 + y) = glm::vec4(tiles_[i].colors[3 * y + x], 1.0f);
                    case_.history.at(x0 + x, y0 + y) = glm::vec4(tiles_[i].history, 1.0f);
                }
        }
        // Unused tiles of the last row repeat the first tile, so no pixel is left at zero by accident.
        for (std::size_t i = tiles_.size(); i < std::size_t(kTilesPerRow) * rows; ++i)
            for (std::uint32_t y = 0; y < 3; ++y)
                for (std::uint32_t x = 0; x < 3; ++x) {
                    const std::uint32_t x0 = 3 * static_cast<std::uint32_t>(i % kTilesPerRow), y0 = 3 * (rows - 1);
                    case_.current.at(x0 + x, y0 + y) = case_.current.at(x, y);
                    case_.history.at(x0 + x, y0 + y) = case_.history.at(x, y);
                }
        if (history_is_current_) case_.history = case_.current;
        if (case_.format == TextureFormat::rgba16f)
            for (Image* image : {&case_.current, &case_.history})
                for (glm::vec4& p : image->pixels) p = glm::unpackHalf4x16(glm::packHalf4x16(p));
        return std::move(case_);
    }

private:
    struct Tile {
        Colors colors;
        glm::vec3 history;
    };
    StressCase case_;
    std::vector<Tile> tiles_;
    bool history_is_current_ = false;
};

// A ray direction exactly perpendicular to `axis` as the emitter writes it (scaled so its largest
// component is 1), with current + v exact, so the shader computes dot(dir, axis) = 0 exactly and
// the reciprocal is infinite: v = (-k_j s) along the unit component u, s along another component j.
// Returns false where no power-of-two s makes current + v exact in float.
bool parallel_offset(const Axis& axis, glm::vec3 current, int other, glm::vec3& v) {
    const ScaledAxis scaled = scale_axis(axis.direction);
    int unit = 0;
    while (scaled.coefficients[unit] != 1.0f) ++unit;
    const int j = (unit + other) % 3;
    for (int e = -30; e <= 100; ++e) {
        const float s = std::ldexp(1.0f, e);
        v = glm::vec3(0.0f);
        v[unit] = -scaled.coefficients[j] * s;
        v[j] = s;
        const glm::vec3 history = current + v;
        if (glm::all(glm::isinf(history))) return false;
        if (history - current == v && glm::length(v) >= 1e-3f * std::max(1.0f, glm::length(current))) return true;
    }
    return false;
}

using CaseMaker = std::function<StressCase(const AxisSet&, Random&)>;

StressCase magnitude_case(std::string name, std::string description, double lo, double hi, Random& random) {
    CaseBuilder b(std::move(name), std::move(description));
    for (int i = 0; i < 6; ++i) b.add_usual_histories(random_colors(random, lo, hi), random);
    return std::move(b).finish();
}

StressCase float_max_case(const AxisSet&, Random& r) {
    CaseBuilder b("float-max", "channels of either sign up to FLT_MAX: sums and differences overflow");
    for (int i = 0; i < 3; ++i) b.add_usual_histories(random_colors(r, 0.5 * kFloatMax, kFloatMax), r);
    for (int i = 0; i < 3; ++i) b.add_usual_histories(random_colors(r, -kFloatMax, kFloatMax), r);
    return std::move(b).finish();
}

StressCase denormal_case(const AxisSet&, Random& r) {
    CaseBuilder b("denormal", "denormal channels (below 1.2e-38), zeros and the smallest denormal");
    for (int i = 0; i < 4; ++i) b.add_usual_histories(random_colors(r, 0, 1e-38), r);
    Colors c = flat(glm::vec3(0.0f));
    c[2] = glm::vec3(std::numeric_limits<float>::denorm_min());
    b.add_usual_histories(c, r);
    return std::move(b).finish();
}

StressCase negative_case(const AxisSet&, Random& r) {
    CaseBuilder b("negative", "negative channels: in [-1, 0], [-1e3, 1e3] and [-6e4, 0]");
    for (int i = 0; i < 2; ++i) b.add_usual_histories(random_colors(r, -1, 0), r);
    for (int i = 0; i < 2; ++i) b.add_usual_histories(random_colors(r, -1e3, 1e3), r);
    for (int i = 0; i < 2; ++i) b.add_usual_histories(random_colors(r, -6e4, 0), r);
    return std::move(b).finish();
}

// All nine colors equal, each of `colors`: the usual histories, then each channel moved by each of
// `offsets`.
StressCase flat_case(std::string name, std::string description, std::array<glm::vec3, 2> colors,
                     std::array<float, 3> offsets, Random& r) {
    CaseBuilder b(std::move(name), std::move(description));
    for (glm::vec3 color : colors) {
        b.add_usual_histories(flat(color), r);
        for (int ch = 0; ch < 3; ++ch)
            for (float offset : offsets) {
                glm::vec3 h = color;
                h[ch] += offset;
                b.add(flat(color), h);
            }
    }
    return std::move(b).finish();
}

StressCase gray_line_case(const AxisSet&, Random& r) {
    CaseBuilder b("gray-line", "all colors gray (on one line): in [0, 1] and [0, 6e4]");
    for (double hi : {1.0, 1.0, 6e4, 6e4}) {
        Colors c = gray_line(r, hi);
        b.add_usual_histories(c, r);
        b.add(c, center(c) + glm::vec3(1.0f, -1.0f, 0.0f) * float(1e-3 * hi));
    }
    return std::move(b).finish();
}

StressCase history_is_current_case(const AxisSet&, Random& r) {
    CaseBuilder b("history-is-current", "every pixel's history equals its current color (LDR, HDR, tiny)");
    for (double hi : {1.0, 6e4, 1e-30})
        for (int i = 0; i < 8; ++i) b.add(random_colors(r, 0, hi), glm::vec3(0.0f));
    b.history_is_current();
    return std::move(b).finish();
}

StressCase parallel_case(const AxisSet& set, Random& r) {
    CaseBuilder b("parallel", "history - current exactly perpendicular to one of the set's axes (dot = 0), "
                              "flat and varied neighborhoods");
    Colors varied = random_colors(r, 0, 1);
    for (glm::vec3& c : varied) c = glm::round(c * 4096.0f) / 4096.0f; // exact sums with power-of-two steps
    for (const Colors& colors : {flat(glm::vec3(0.375f)), flat(glm::vec3(5e4f)), varied})
        for (const Axis& axis : set.axes)
            for (int other : {1, 2}) {
                glm::vec3 v;
                if (parallel_offset(axis, center(colors), other, v)) b.add(colors, center(colors) + v);
            }
    return std::move(b).finish();
}

StressCase nan_history_case(const AxisSet&, Random& r) {
    CaseBuilder b("nan-history", "history with NaN in one or all channels");
    for (double hi : {1.0, 6e4}) {
        Colors c = random_colors(r, 0, hi);
        const glm::vec3 m = center(c);
        for (glm::vec3 h : {glm::vec3(kNaN, m.y, m.z), glm::vec3(m.x, kNaN, m.z), glm::vec3(kNaN)}) b.add(c, h);
    }
    return std::move(b).finish();
}

StressCase inf_history_case(const AxisSet&, Random& r) {
    CaseBuilder b("inf-history", "history with +Inf or -Inf channels");
    for (double hi : {1.0, 6e4}) {
        Colors c = random_colors(r, 0, hi);
        const glm::vec3 m = center(c);
        for (glm::vec3 h :
             {glm::vec3(kInf, m.y, m.z), glm::vec3(m.x, -kInf, m.z), glm::vec3(kInf, -kInf, 0.0f), glm::vec3(kInf)})
            b.add(c, h);
    }
    return std::move(b).finish();
}

// Random neighborhoods in [0, 1] with neighbor `at` (not the pixel) replaced by each of `bad`.
StressCase bad_neighbor_case(std::string name, std::string description, std::initializer_list<glm::vec3> bad, int at,
                             Random& r) {
    CaseBuilder b(std::move(name), std::move(description));
    for (glm::vec3 color : bad) {
        Colors c = random_colors(r, 0, 1);
        c[at] = color;
        b.add_usual_histories(c, r);
    }
    return std::move(b).finish();
}

StressCase rgba16f_case(const AxisSet&, Random& r) {
    CaseBuilder b("rgba16f",
                  "half-float textures: channels up to 65504, some exactly 65504, histories up to "
                  "7e4 (Inf in half)",
                  TextureFormat::rgba16f);
    for (int i = 0; i < 4; ++i) {
        Colors c = random_colors(r, 0, kHalfMax);
        for (glm::vec3& color : c)
            for (int ch = 0; ch < 3; ++ch)
                if (r.uniform() < 0.3) color[ch] = kHalfMax;
        b.add_usual_histories(c, r);
        b.add(c, glm::vec3(kHalfMax));
        b.add(c, glm::vec3(7e4f, 1.0f, 1.0f));
    }
    return std::move(b).finish();
}

// Every case, in the order of the stress matrix; each draws from its own random stream.
const std::vector<CaseMaker>& case_makers() {
    static const std::vector<CaseMaker> makers = {
        [](const AxisSet&, Random& r) {
            return magnitude_case("hdr-1e3", "HDR colors, channels in [0, 1e3]", 0, 1e3, r);
        },
        [](const AxisSet&, Random& r) {
            return magnitude_case("hdr-6e4", "HDR colors, channels in [0, 6e4]", 0, 6e4, r);
        },
        [](const AxisSet&, Random& r) {
            return magnitude_case("hdr-1e6", "HDR colors, channels in [0, 1e6]", 0, 1e6, r);
        },
        [](const AxisSet&, Random& r) {
            return magnitude_case("near-max", "channels in [1e37, 1e38]: projections near the float maximum", 1e37,
                                  1e38, r);
        },
        float_max_case,
        [](const AxisSet&, Random& r) { return magnitude_case("tiny", "channels in [0, 1e-30]", 0, 1e-30, r); },
        denormal_case,
        negative_case,
        [](const AxisSet&, Random& r) {
            return flat_case("flat-0.37", "all nine colors equal: gray 0.37 and (0.37, 0.2, 0.9)",
                             {glm::vec3(0.37f), glm::vec3(0.37f, 0.2f, 0.9f)}, {-1e-3f, 1e-3f, 1.0f}, r);
        },
        [](const AxisSet&, Random& r) {
            return flat_case("flat-5e4", "all nine colors equal: gray 5e4 and (5e4, 2e4, 6e4)",
                             {glm::vec3(5e4f), glm::vec3(5e4f, 2e4f, 6e4f)}, {-1.0f, 1.0f, 1e3f}, r);
        },
        gray_line_case,
        history_is_current_case,
        parallel_case,
        nan_history_case,
        inf_history_case,
        [](const AxisSet&, Random& r) {
            return bad_neighbor_case("nan-neighbor", "one neighbor (not the pixel) with NaN in one or all channels",
                                     {glm::vec3(kNaN, 0.5f, 0.5f), glm::vec3(kNaN)}, 1, r);
        },
        [](const AxisSet&, Random& r) {
            return bad_neighbor_case("inf-neighbor", "one neighbor (not the pixel) with +Inf or -Inf channels",
                                     {glm::vec3(kInf, 0.5f, 0.5f), glm::vec3(-kInf), glm::vec3(kInf, -kInf, 1.0f)}, 7,
                                     r);
        },
        rgba16f_case,
    };
    return makers;
}

} // namespace

std::size_t stress_case_count() { return case_makers().size(); }

std::vector<StressCase> make_stress_cases(const AxisSet& set, std::uint64_t seed) {
    std::vector<StressCase> cases;
    std::uint64_t stream = 0;
    for (const CaseMaker& make : case_makers()) {
        Random random(seed * 0x100000001b3ull + ++stream);
        cases.push_back(make(set, random));
    }
    return cases;
}

} // namespace kdop
