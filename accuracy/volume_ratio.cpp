#include "accuracy/volume_ratio.h"

#include "accuracy/volume.h"
#include "images/random.h"
#include "reference/cpu_clip.h"

#include <glm/common.hpp>

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

namespace kdop {

Result<std::vector<SolidPixel>> sample_solid_pixels(const Image& current, Neighborhood shape, std::size_t count,
                                                    std::uint64_t seed) {
    std::vector<std::uint32_t> order(current.pixels.size());
    std::iota(order.begin(), order.end(), 0u);
    Random random(seed);
    for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[random.next() % i]); // Fisher-Yates

    const std::vector<glm::ivec2> offsets = reference_offsets(shape);
    std::vector<glm::dvec3> neighborhood(offsets.size());
    std::vector<SolidPixel> sample;
    for (std::size_t i = 0; i < order.size() && sample.size() < count; ++i) {
        const std::uint32_t x = order[i] % current.width, y = order[i] / current.width;
        gather_neighborhood(current, x, y, offsets, neighborhood);
        glm::dvec3 lo = neighborhood[0], hi = neighborhood[0];
        for (const glm::dvec3& p : neighborhood) lo = glm::min(lo, p), hi = glm::max(hi, p);
        const double side = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
        auto volume = hull_volume(neighborhood);
        if (!volume) return std::unexpected(volume.error());
        if (*volume > 0 && *volume >= kSolidHull * side * side * side) sample.push_back({x, y, *volume});
    }
    return sample;
}

Result<VolumeRatio> volume_ratio(const Image& current, std::span<const SolidPixel> sample, const AxisSet& set,
                                 Mode mode, Neighborhood shape, double gamma) {
    const std::vector<glm::dvec3> axes = unit_axes(set);
    const std::vector<glm::ivec2> offsets = reference_offsets(shape);
    std::vector<glm::dvec3> neighborhood(offsets.size());
    std::vector<double> ratios;
    for (const SolidPixel& p : sample) {
        gather_neighborhood(current, p.x, p.y, offsets, neighborhood);
        const glm::dvec3 centroid = std::accumulate(neighborhood.begin(), neighborhood.end(), glm::dvec3(0)) /
                                    double(neighborhood.size()); // strictly inside: the hull is solid, slabs padded
        const auto slabs = reference_slabs(axes, neighborhood, glm::dvec3(current.at(p.x, p.y)), mode, gamma);
        auto volume = slab_volume(slabs, centroid);
        if (!volume) return fail(fmt::format("{} at pixel ({}, {}): {}", set.name, p.x, p.y, volume.error().message));
        ratios.push_back(*volume / p.hull_volume);
    }
    VolumeRatio r;
    r.pixels = ratios.size();
    if (ratios.empty()) return r;
    r.mean = std::accumulate(ratios.begin(), ratios.end(), 0.0) / double(ratios.size());
    std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
    r.median = ratios[ratios.size() / 2]; // the upper median for an even count
    return r;
}

} // namespace kdop
