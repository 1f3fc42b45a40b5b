#include "reference/cpu_clip.h"

#include "core/parallel_for.h"
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace kdop {

bool reference_history_usable(const glm::dvec3& current, const glm::dvec3& history) {
    const glm::dvec3 reach = glm::abs(history - current) + glm::abs(current);
    const double sum = reach.x + reach.y + reach.z;
    return std::isfinite(sum) && sum <= double(std::numeric_limits<float>::max());
}

std::vector<ReferenceSlab> reference_slabs(std::span<const glm::dvec3> unit_axes,
                                           std::span<const glm::dvec3> neighborhood, const glm::dvec3& current,
                                           Mode mode, double gamma) {
    const double n = static_cast<double>(neighborhood.size());
    const double e = kReferencePadding;
    std::vector<ReferenceSlab> slabs;
    for (const glm::dvec3& axis : unit_axes) {
        const double p = glm::dot(current, axis);
        double lo, hi;
        if (mode == Mode::clip) {
            lo = std::numeric_limits<double>::infinity();
            hi = -lo;
            for (const glm::dvec3& c : neighborhood) {
                lo = std::min(lo, glm::dot(c, axis));
                hi = std::max(hi, glm::dot(c, axis));
            }
        } else {
            double mean = 0;
            for (const glm::dvec3& c : neighborhood) mean += glm::dot(c, axis);
            mean /= n;
            double variance = 0; // two passes: exact enough in double for any input
            for (const glm::dvec3& c : neighborhood)
                variance += (glm::dot(c, axis) - mean) * (glm::dot(c, axis) - mean);
            const double sigma = std::sqrt(variance / n);
            lo = mean - gamma * sigma;
            hi = mean + gamma * sigma;
        }
        if (mode == Mode::clip)
            slabs.push_back({axis, lo - e, hi + e});
        else
            slabs.push_back({axis, std::min(lo, p) - e, std::max(hi, p) + e});
    }
    return slabs;
}

double reference_exit(std::span<const ReferenceSlab> slabs, const glm::dvec3& current, const glm::dvec3& history) {
    const glm::dvec3 dir = history - current;
    double t = 1.0;
    for (const ReferenceSlab& slab : slabs) {
        const double p = glm::dot(current, slab.axis);
        const double d = glm::dot(dir, slab.axis);
        if (d > 0) t = std::min(t, (slab.hi - p) / d);
        if (d < 0) t = std::min(t, (slab.lo - p) / d);
    }
    return std::clamp(t, 0.0, 1.0);
}

glm::dvec3 reference_clip(std::span<const glm::dvec3> unit_axes, std::span<const glm::dvec3> neighborhood,
                          const glm::dvec3& current, const glm::dvec3& history, Mode mode, double gamma,
                          Numerics numerics) {
    if (numerics == Numerics::hardened && !reference_history_usable(current, history)) return current;
    const auto slabs = reference_slabs(unit_axes, neighborhood, current, mode, gamma);
    return current + reference_exit(slabs, current, history) * (history - current);
}

std::vector<glm::dvec3> unit_axes(const AxisSet& set) {
    std::vector<glm::dvec3> axes;
    for (const Axis& a : set.axes) axes.push_back(unit_direction(a.direction));
    return axes;
}

std::vector<glm::ivec2> reference_offsets(Neighborhood n) {
    std::vector<glm::ivec2> offsets;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            if (n == Neighborhood::n9 || dx == 0 || dy == 0) offsets.emplace_back(dx, dy);
    return offsets;
}

void gather_neighborhood(const Image& image, std::uint32_t x, std::uint32_t y, std::span<const glm::ivec2> offsets,
                         std::span<glm::dvec3> out) {
    for (std::size_t i = 0; i < offsets.size(); ++i)
        out[i] = glm::dvec3(image.clamped(int(x) + offsets[i].x, int(y) + offsets[i].y));
}

Image reference_rectify(const AxisSet& set, Mode mode, Neighborhood n, const Image& current, const Image& history,
                        double gamma, Numerics numerics) {
    const std::vector<glm::dvec3> axes = unit_axes(set);
    const std::vector<glm::ivec2> offsets = reference_offsets(n);
    Image out(current.width, current.height);
    parallel_for(current.height, 0, [&](std::size_t row) {
        const auto y = std::uint32_t(row);
        std::vector<glm::dvec3> neighborhood(offsets.size());
        for (std::uint32_t x = 0; x < current.width; ++x) {
            gather_neighborhood(current, x, y, offsets, neighborhood);
            glm::dvec3 r = reference_clip(axes, neighborhood, glm::dvec3(current.at(x, y)),
                                          glm::dvec3(history.at(x, y)), mode, gamma, numerics);
            out.at(x, y) = glm::vec4(glm::vec3(r), 1.0f);
        }
    });
    return out;
}

} // namespace kdop
