// What a FLIP error map says beyond its mean, as NVlabs/flip's tool prints it: the weighted median
// and quartiles, the minimum and maximum, and the error histogram; with them the plain median and
// quartiles, which weigh every pixel alike.
//
// The weighted percentiles are NVlabs/flip's definition (pooling.h, getWeightedPercentile): the
// map's values in a histogram of `kFlipHistogramBuckets` equal buckets over [0, 1], each bucket
// weighted by its count times its center; the p-th weighted percentile lies in the bucket where
// that weight, summed from 0, passes p times the whole, at the share of the bucket's weight still
// needed. A pixel's vote grows with its error, so a few large errors move them where they hardly
// move the plain median. The plain percentiles interpolate linearly between order statistics
// (numpy's default); NVlabs' tool does not print them.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace kdop {

inline constexpr std::size_t kFlipHistogramBuckets = 100; // NVlabs/flip's

struct FlipStatistics {
    double mean = 0;
    double weighted_median = 0, weighted_q1 = 0, weighted_q3 = 0; // NVlabs/flip's
    double median = 0, q1 = 0, q3 = 0;                            // every pixel alike
    double min = 0, max = 0;
};

// The pixel counts of `map` (FLIP values in [0, 1]) in kFlipHistogramBuckets buckets; a value of
// exactly 1 counts in the last.
std::vector<std::size_t> flip_histogram(std::span<const float> map);

// `map`'s statistics; `mean` as flip.h's mean_error sums it. A map must not be empty.
FlipStatistics flip_statistics(std::span<const float> map);

} // namespace kdop
