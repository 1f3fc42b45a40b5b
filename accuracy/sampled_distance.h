// The mean distance to the ideal clip (accuracy_metrics.h) of several axis sets' clips on a seeded
// sample of pixels, in the CPU reference (clip mode, hardened numerics): the measure `kdop accuracy`
// takes over every pixel on the device, cheap enough for `kdop optimize` to report beside the
// volume it minimizes (each sampled pixel costs one exact LP: up to about 150 microseconds).
#pragma once

#include "accuracy/accuracy_inputs.h"
#include "core/result.h"
#include "fit/axis_fit.h"
#include "generator/variant_spec.h"
#include "harness/progress.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace kdop {

struct SampledDistances {
    std::vector<double> mean; // per set, in units of S (accuracy_metrics.h), over every sampled pixel
    std::size_t pixels = 0;   // sampled pixels over all pairs
};

// Up to `per_pair` pixels of each pair, in a random order fixed by `seed` (every pixel where the
// pair has fewer), each with where the ideal clip stops its history. `progress` advances once per
// pair. An ideal clip without a solution is an error naming the pair and the pixel.
Result<std::vector<ClipSample>> ideal_clip_samples(std::span<const AccuracyPair> pairs, Neighborhood shape,
                                                   std::size_t per_pair, std::uint64_t seed,
                                                   Progress* progress = nullptr);

// The mean distance of each set's clip (the CPU reference's, hardened) to the ideal clip on those
// samples. Each set is given by its unit axes.
Result<SampledDistances> sampled_ideal_distances(std::span<const AccuracyPair> pairs,
                                                 std::span<const std::vector<glm::dvec3>> sets, Neighborhood shape,
                                                 std::size_t per_pair, std::uint64_t seed,
                                                 Progress* progress = nullptr);
SampledDistances sampled_ideal_distances(std::span<const ClipSample> samples,
                                         std::span<const std::vector<glm::dvec3>> sets);

} // namespace kdop
