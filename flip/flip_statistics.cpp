#include "flip/flip_statistics.h"

#include "flip/flip.h"
#include "harness/statistics.h"

#include <algorithm>
#include <bit>
#include <cstdint>

namespace kdop {
namespace {

// NVlabs/flip's printed weighted percentile (see the header), in its float arithmetic: the first of
// the `sorted` values at which their running sum passes p times `total`.
float weighted_percentile(const std::vector<float>& sorted, float total, float p) {
    float running = 0;
    for (float value : sorted) {
        running += value;
        if (running > p * total) return value;
    }
    return 0;
}

// `map`'s values in ascending order, by a two-pass radix sort of their bits (negative values' bits
// flipped, as IEEE-754 orders them): on a 1920x1080 map of FLIP-like values, 21 ms where std::sort
// of doubles took 99 ms, a tenth of what `kdop flip --cpu` spends past its start. (Boost's
// spreadsort does the same, but no other part of kdop needs Boost.)
std::vector<float> sorted_values(std::span<const float> map) {
    auto key = [](float value) {
        const auto bits = std::bit_cast<std::uint32_t>(value);
        return bits & 0x80000000u ? ~bits : bits | 0x80000000u;
    };
    std::vector<std::uint32_t> keys(map.size()), other(map.size());
    std::ranges::transform(map, keys.begin(), key);
    for (int shift : {0, 16}) {
        std::vector<std::size_t> start(65537, 0); // where each digit's run begins
        for (std::uint32_t k : keys) ++start[((k >> shift) & 0xffffu) + 1];
        for (std::size_t d = 1; d < start.size(); ++d) start[d] += start[d - 1];
        for (std::uint32_t k : keys) other[start[(k >> shift) & 0xffffu]++] = k;
        keys.swap(other);
    }
    std::vector<float> sorted(map.size());
    std::ranges::transform(keys, sorted.begin(), [](std::uint32_t k) {
        return std::bit_cast<float>(k & 0x80000000u ? k & 0x7fffffffu : ~k);
    });
    return sorted;
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
    const std::vector<float> values = sorted_values(map); // once, for the six quantiles and the extremes
    float total = 0;                                      // in the map's order, as NVlabs/flip's tool sums it
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
