#include "stress/stress_check.h"

#include "reference/cpu_clip.h"

#include <fmt/format.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace kdop {
namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

double largest_magnitude(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// Distance from `point` to the segment a..b.
double distance_to_segment(const glm::dvec3& point, const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 ab = b - a;
    const double length2 = glm::dot(ab, ab);
    const double t = length2 > 0 ? std::clamp(glm::dot(point - a, ab) / length2, 0.0, 1.0) : 0.0;
    return glm::length(point - (a + t * ab));
}

// How far `point` lies outside the slabs (0 inside), and its margin: the distance to the nearest
// slab plane, negative outside.
double outside_slabs(const std::vector<ReferenceSlab>& slabs, const glm::dvec3& point) {
    double outside = 0;
    for (const ReferenceSlab& s : slabs) {
        const double q = glm::dot(point, s.axis);
        outside = std::max({outside, s.lo - q, q - s.hi});
    }
    return outside;
}
double margin(const std::vector<ReferenceSlab>& slabs, const glm::dvec3& point) {
    double m = INFINITY;
    for (const ReferenceSlab& s : slabs) {
        const double q = glm::dot(point, s.axis);
        m = std::min({m, q - s.lo, s.hi - q});
    }
    return m;
}

std::string text(const glm::dvec3& v) { return fmt::format("({:.9g}, {:.9g}, {:.9g})", v.x, v.y, v.z); }

// Records one check of `invariant`: `distance` (in units of S) over the tolerance, or `failed`.
void record(InvariantTally& tally, bool failed, double distance, const std::string& context) {
    ++tally.checked;
    if (std::isfinite(distance)) tally.worst = std::max(tally.worst, distance);
    if (!failed) return;
    if (tally.violated++ == 0) tally.example = context;
}

} // namespace

const char* invariant_code(Invariant i) {
    constexpr const char* codes[] = {"N", "D", "S", "K", "R", "C"};
    return codes[static_cast<int>(i)];
}

const char* invariant_name(Invariant i) {
    constexpr const char* names[] = {"finite", "defined", "segment", "inside", "range", "classify"};
    return names[static_cast<int>(i)];
}

const char* invariant_description(Invariant i) {
    switch (i) {
    case Invariant::finite: return "finite current gives a finite output, whatever the history or a neighbor holds";
    case Invariant::defined:
        return "a history with NaN or Inf, or too far out to project, gives exactly the current color";
    case Invariant::segment: return "the output lies on the segment current..history";
    case Invariant::inside: return "the output lies inside every padded slab of the k-DOP";
    case Invariant::range: return "clips with X, Y, Z axes: every channel within the neighborhood's padded range";
    case Invariant::classify: return "where GPU and reference disagree on history inside/outside, it lies on a slab";
    }
    return "";
}

std::size_t CheckResult::violations() const {
    std::size_t n = 0;
    for (const InvariantTally& t : tallies) n += t.violated;
    return n;
}

ClipUnderTest::ClipUnderTest(const VariantSpec& spec, double gamma_)
    : unit_axes(kdop::unit_axes(spec.set)), mode(spec.mode), neighborhood(spec.neighborhood), gamma(gamma_),
      numerics(spec.numerics) {
    auto has = [&](glm::dvec3 e) {
        return std::ranges::any_of(unit_axes, [&](const glm::dvec3& a) { return std::abs(glm::dot(a, e)) == 1.0; });
    };
    has_xyz = has({1, 0, 0}) && has({0, 1, 0}) && has({0, 0, 1});
}

CheckResult check_invariants(const ClipUnderTest& clip, const Image& current, const Image& history,
                             const Image& output) {
    const std::vector<glm::ivec2> offsets = reference_offsets(clip.neighborhood);
    const double tol = kStressTolerance;
    CheckResult result;
    std::vector<glm::dvec3> neighborhood(offsets.size());
    for (std::uint32_t y = 0; y < current.height; ++y)
        for (std::uint32_t x = 0; x < current.width; ++x) {
            ++result.pixels;
            const glm::dvec3 cur(glm::vec3(current.at(x, y))), hist(glm::vec3(history.at(x, y)));
            const glm::dvec3 out(glm::vec3(output.at(x, y)));
            if (!finite(cur)) continue; // nothing is promised
            bool neighbors_finite = true;
            double s = std::max({1.0, largest_magnitude(cur), finite(hist) ? largest_magnitude(hist) : 0.0});
            for (std::size_t i = 0; i < offsets.size(); ++i) {
                neighborhood[i] = glm::dvec3(glm::vec3(current.clamped(int(x) + offsets[i].x, int(y) + offsets[i].y)));
                if (finite(neighborhood[i]))
                    s = std::max(s, largest_magnitude(neighborhood[i]));
                else
                    neighbors_finite = false;
            }
            const std::string context =
                fmt::format("at ({}, {}): current {}, history {}, output {}", x, y, text(cur), text(hist), text(out));

            record(result[Invariant::finite], !finite(out), 0, context);
            if (!reference_history_usable(cur, hist)) {
                record(result[Invariant::defined], out != cur, 0, context);
                continue;
            }
            if (!finite(out)) continue; // counted above; the distances below would mean nothing
            const double off_segment = distance_to_segment(out, cur, hist) / s;
            record(result[Invariant::segment], off_segment > tol, off_segment, context);
            if (!neighbors_finite) continue;

            const auto slabs = reference_slabs(clip.unit_axes, neighborhood, cur, clip.mode, clip.gamma);
            const double outside = outside_slabs(slabs, out) / s;
            record(result[Invariant::inside], outside > tol, outside, context);
            if (clip.has_xyz && clip.mode == Mode::clip) {
                const double padding = kReferencePadding;
                double beyond = 0;
                for (int ch = 0; ch < 3; ++ch) {
                    double lo = INFINITY, hi = -INFINITY;
                    for (const glm::dvec3& c : neighborhood) {
                        lo = std::min(lo, c[ch]);
                        hi = std::max(hi, c[ch]);
                    }
                    beyond = std::max({beyond, lo - padding - out[ch], out[ch] - hi - padding});
                }
                record(result[Invariant::range], beyond / s > tol, beyond / s, context);
            }
            // The GPU accepted the history if it returned it, up to the rounding of current + 1 * dir
            // (a few ulps of the pair's own magnitude, not of S). A history that close to current
            // cannot be told accepted from clipped.
            const double ulps = 0x1p-21 * std::max(largest_magnitude(cur), largest_magnitude(hist));
            if (largest_magnitude(hist - cur) <= ulps) continue;
            const bool gpu_inside = largest_magnitude(out - hist) <= ulps;
            const double reference_t = reference_exit(slabs, cur, hist);
            const double off_slab = gpu_inside == (reference_t == 1.0) ? 0.0 : std::abs(margin(slabs, hist)) / s;
            record(result[Invariant::classify], off_slab > tol, off_slab,
                   fmt::format("{}; the reference clips at t = {:.9g}", context, reference_t));
        }
    return result;
}

} // namespace kdop
