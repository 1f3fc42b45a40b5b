#include "flip/flip_statistics.h"

#include "flip/flip.h"
#include "harness/statistics.h"

#include <algorithm>

namespace kdop {
namespace {

// NVlabs/flip's weighted percentile of a histogram (see the header), stated here from its
// definition: the bucket where the running weight first passes p times the total, and the share
// of that bucket's weight still needed there. Where none passes (p = 1), the last bucket.
double weighted_percentile(const std::vector<std::size_t>& histogram, double p) {
    const double step = 1.0 / double(histogram.size());
    auto weight = [&](std::size_t b) { return double(histogram[b]) * (double(b) + 0.5) * step; };
    double total = 0;
    for (std::size_t b = 0; b < histogram.size(); ++b) total += weight(b);
    double below = 0;
    std::size_t b = 0;
    for (; b + 1 < histogram.size() && below + weight(b) <= p * total; ++b) below += weight(b);
    if (b + 1 == histogram.size() && below + weight(b) <= p * total) below += weight(b);
    return (double(b) + (p * total - below) / weight(b)) * step;
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
    const std::vector<std::size_t> histogram = flip_histogram(map);
    std::vector<double> values(map.begin(), map.end());
    std::sort(values.begin(), values.end()); // once, for the three quantiles and the extremes
    return {.mean = mean_error(map),
            .weighted_median = weighted_percentile(histogram, 0.5),
            .weighted_q1 = weighted_percentile(histogram, 0.25),
            .weighted_q3 = weighted_percentile(histogram, 0.75),
            .median = quantile_of_sorted(values, 0.5),
            .q1 = quantile_of_sorted(values, 0.25),
            .q3 = quantile_of_sorted(values, 0.75),
            .min = values.front(),
            .max = values.back()};
}

} // namespace kdop
