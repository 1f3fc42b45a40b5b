#include "flip/flip_statistics.h"

#include "flip/flip.h"
#include "harness/statistics.h"

#include <algorithm>

namespace kdop {
namespace {

// NVlabs/flip's printed weighted percentile (see the header), in its float arithmetic: the first of
// the `sorted` values at which their running sum passes p times `total`.
float weighted_percentile(const std::vector<double>& sorted, float total, float p) {
    float running = 0;
    for (double value : sorted) {
        running += float(value); // the map's floats, sorted as doubles
        if (running > p * total) return float(value);
    }
    return 0;
}

} // namespace

std::vector<std::size_t> flip_histogram(std::span<const float> map) {
    std::vector<std::size_t> histogram(kFlipHistogramBuckets, 0);
    for (float value : map) {
        const auto bucket = std::size_t(double(value) * double(kFlipHistogramBuckets));
        ++histogram[std::min(bucket, kFlipHistogramBuckets - 1)];
    }
    return histogram;
}

FlipStatistics flip_statistics(std::span<const float> map) {
    std::vector<double> values(map.begin(), map.end());
    std::sort(values.begin(), values.end()); // once, for the six quantiles and the extremes
    float total = 0;                         // in the map's order, as NVlabs/flip's tool sums it
    for (float value : map) total += value;
    return {.mean = mean_error(map),
            .weighted_median = weighted_percentile(values, total, 0.5f),
            .weighted_q1 = weighted_percentile(values, total, 0.25f),
            .weighted_q3 = weighted_percentile(values, total, 0.75f),
            .median = quantile_of_sorted(values, 0.5),
            .q1 = quantile_of_sorted(values, 0.25),
            .q3 = quantile_of_sorted(values, 0.75),
            .min = values.front(),
            .max = values.back()};
}

} // namespace kdop
