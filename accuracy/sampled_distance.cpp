#include "accuracy/sampled_distance.h"

#include "accuracy/accuracy_metrics.h"
#include "accuracy/ideal_clip.h"
#include "images/random.h"
#include "reference/cpu_clip.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <numeric>

namespace kdop {

Result<std::vector<ClipSample>> ideal_clip_samples(std::span<const AccuracyPair> pairs, Neighborhood shape,
                                                   std::size_t per_pair, std::uint64_t seed, Progress* progress) {
    std::vector<ClipSample> samples;
    const std::vector<glm::ivec2> offsets = reference_offsets(shape);
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
            ClipSample s;
            s.neighborhood.resize(offsets.size());
            gather_neighborhood(pair.current, x, y, offsets, s.neighborhood);
            const glm::vec4& pixel = pair.current.pixels[order[i]];
            s.current = glm::dvec3(pixel);
            s.history = glm::dvec3(pair.history.pixels[order[i]]);
            const std::optional<double> t = ideal.exit(s.neighborhood, s.current, s.history);
            if (!t || !std::isfinite(*t))
                return std::unexpected(
                    Error{fmt::format("{}: the ideal clip at pixel ({}, {}) has no solution", pair.name, x, y)});
            s.ideal = s.current + *t * (s.history - s.current);
            s.scale = pixel_magnitude(pixel);
            samples.push_back(std::move(s));
        }
        if (progress) progress->advance(pair.name);
    }
    return samples;
}

SampledDistances sampled_ideal_distances(std::span<const ClipSample> samples,
                                         std::span<const std::vector<glm::dvec3>> sets) {
    SampledDistances out;
    out.pixels = samples.size();
    for (const std::vector<glm::dvec3>& axes : sets) {
        double sum = 0;
        for (const ClipSample& s : samples)
            sum += glm::distance(reference_clip(axes, s.neighborhood, s.current, s.history, Mode::clip, 1.0), s.ideal) /
                   s.scale;
        out.mean.push_back(samples.empty() ? NAN : sum / double(samples.size()));
    }
    return out;
}

Result<SampledDistances> sampled_ideal_distances(std::span<const AccuracyPair> pairs,
                                                 std::span<const std::vector<glm::dvec3>> sets, Neighborhood shape,
                                                 std::size_t per_pair, std::uint64_t seed, Progress* progress) {
    auto samples = ideal_clip_samples(pairs, shape, per_pair, seed, progress);
    if (!samples) return std::unexpected(samples.error());
    return sampled_ideal_distances(*samples, sets);
}

} // namespace kdop
