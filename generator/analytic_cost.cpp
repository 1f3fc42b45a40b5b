#include "generator/analytic_cost.h"

#include "generator/scaled_axis.h"
#include "generator/variant_spec.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <optional>
#include <set>
#include <tuple>
#include <vector>

namespace kdop {

namespace {

// The two scaled (not unit) components of an axis when they have one magnitude, with whether their
// signs agree: the emitter projects them as (c.a +- c.b) * k, a sum every axis with the same pair
// shares. Empty otherwise.
std::optional<std::tuple<int, int, bool>> equal_scaled_pair(const glm::vec3& k) {
    std::vector<int> scaled;
    for (int c = 0; c < 3; ++c)
        if (k[c] != 0.0f && std::abs(k[c]) != 1.0f) scaled.push_back(c);
    if (scaled.size() != 2 || std::abs(k[scaled[0]]) != std::abs(k[scaled[1]])) return std::nullopt;
    return std::tuple{scaled[0], scaled[1], k[scaled[0]] == k[scaled[1]]};
}

} // namespace

std::size_t frame_float_ops(const AxisSet& set, Mode mode, Neighborhood neighborhood, bool relative) {
    assert(mode == Mode::clip || mode == Mode::varclip);
    const std::size_t n = neighborhood_offsets(neighborhood).size();
    relative = relative || mode == Mode::varclip;
    // The colors projected on every axis: the N - 1 other neighbors and the ray, and, absolute, the
    // current color.
    const std::size_t colors = relative ? n : n + 1;
    std::size_t ops = 18; // ray direction; usable history; current + t * dir
    if (relative) ops += 3 * (n - 1);
    if (mode == Mode::varclip) ops += 11; // the scaled frame
    std::set<std::tuple<int, int, bool>> pair_sums;
    for (const Axis& axis : set.axes) {
        // Counted on the scaled axis the emitter writes, whose zero components are those of the file.
        const ScaledAxis scaled = scale_axis(axis.direction);
        std::size_t m = 0;
        for (int c = 0; c < 3; ++c) m += scaled.coefficients[c] != 0.0f;
        std::size_t per_projection = m - 1;
        if (auto pair = equal_scaled_pair(scaled.coefficients)) { // one multiply-add on the shared sum
            pair_sums.insert(*pair);
            per_projection = m - 2;
        }
        ops += colors * per_projection;
        if (mode == Mode::varclip)
            ops += 2 * n + 11;
        else if (relative)
            ops += 2 * n + 3;
        else
            ops += 2 * n + 5;
    }
    return ops + colors * pair_sums.size(); // each shared sum, once per color
}

Frame hardened_frame(const AxisSet& set, Mode mode, Neighborhood neighborhood) {
    if (mode == Mode::varclip) return Frame::relative;
    const std::size_t absolute = frame_float_ops(set, mode, neighborhood, false) + 2 * set.axes.size();
    return frame_float_ops(set, mode, neighborhood, true) < absolute ? Frame::relative : Frame::absolute;
}

std::size_t analytic_min_float_ops(const AxisSet& set, Mode mode, Neighborhood neighborhood) {
    return std::min(frame_float_ops(set, mode, neighborhood, true), frame_float_ops(set, mode, neighborhood, false));
}

} // namespace kdop
