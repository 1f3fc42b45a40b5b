#include "sampled_distance.h"

#include "accuracy_metrics.h"
#include "cpu_clip.h"
#include "ideal_clip.h"
#include "random.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <numeric>

namespace kdop {

Result<SampledDistances> sampled_ideal_distances(std::span<const AccuracyPair> pairs,
                                                 std::span<const std::vector<glm::dvec3>> sets, Neighborhood shape,
                                                 std::size_t per_pair, std::uint64_t seed, Progress* progress) {
    SampledDistances out;
    std::vector<double> sums(sets.size(), 0.0);
    const std::vector<glm::ivec2> offsets = reference_offsets(shape);
    std::vector<glm::dvec3> neighborhood(offsets.size());
    IdealClipper ideal;
    Random random(seed);
    for (const AccuracyPair& pair : pairs) {
        std::vector<std::uint32_t> order(pair.current.pixels.size());
        std::iota(order.begin(), order.end(), 0u);
        const std::size_t count = std::min(per_pair, order.size());
        for (std::size_t i = 0; i < count; ++i) // the first `count` of a Fisher-Yates shuffle
            std::swap(order[i], order[i + random.next() % (order.size() - i)]);
        for (std::size_t i = 0; i < count; ++i) {
            const std::uint32_t x = order[i] % pair.current.width, y = order[i] / pair.current.width;
            gather_neighborhood(pair.current, x, y, offsets, neighborhood);
            const glm::vec4& pixel = pair.current.pixels[order[i]];
            const glm::dvec3 c(pixel), h(pair.history.pixels[order[i]]);
            const std::optional<double> t = ideal.exit(neighborhood, c, h);
            if (!t || !std::isfinite(*t))
                return std::unexpected(
                    Error{fmt::format("{}: the ideal clip at pixel ({}, {}) has no solution", pair.name, x, y)});
            const glm::dvec3 target = c + *t * (h - c);
            const double s = pixel_magnitude(pixel);
            for (std::size_t k = 0; k < sets.size(); ++k)
                sums[k] += glm::distance(reference_clip(sets[k], neighborhood, c, h, Mode::clip, 1.0), target) / s;
        }
        out.pixels += count;
        if (progress) progress->advance(pair.name);
    }
    for (double sum : sums) out.mean.push_back(out.pixels ? sum / double(out.pixels) : NAN);
    return out;
}

} // namespace kdop
