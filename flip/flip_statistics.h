// What a FLIP error map says beyond its mean, as NVlabs/flip's tool prints it: the weighted median
// and quartiles, the minimum and maximum, and the error histogram; with them the plain median and
// quartiles, which weigh every pixel alike.
//
// The weighted percentiles are those NVlabs/flip's tool prints (pooling.h, getPercentile with
// bWeighted): the map's values sorted, the p-th weighted percentile is the first value at which
// their running sum passes p times the sum of all, both summed in float as the tool sums them (the
// total in the map's order), so on the same map the figures are the tool's to the last digit; 0
// for a map of zeros. A pixel's vote grows with its error, so a few large errors move them where they hardly
// move the plain median. (The tool's histogram plot marks another weighted median, interpolated in
// its histogram, getWeightedPercentile; the tool does not print that one.) The plain percentiles
// interpolate linearly between order statistics (numpy's default); NVlabs' tool does not print them.
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
