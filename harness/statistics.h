// Order statistics for timing samples. Medians and quartiles, not means: on a shared machine a
// few dispatches are delayed by other work, and those outliers should not move the figure.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace kdop {

// The q-quantile (0..1) of samples already in ascending order, by linear interpolation between order
// statistics; NaN for none. For several quantiles of one large set: one sort, not one each.
template <class T> // float or double samples; the interpolation is in double
double quantile_of_sorted(const std::vector<T>& samples, double q) {
    if (samples.empty()) return NAN;
    const double position = q * double(samples.size() - 1);
    const std::size_t below = static_cast<std::size_t>(position);
    const std::size_t above = std::min(below + 1, samples.size() - 1);
    const double low = samples[below], high = samples[above];
    return low + (position - double(below)) * (high - low);
}

// The q-quantile (0..1) by linear interpolation between order statistics; NaN for no samples.
inline double quantile(std::vector<double> samples, double q) {
    std::sort(samples.begin(), samples.end());
    return quantile_of_sorted(samples, q);
}

inline double median(const std::vector<double>& samples) { return quantile(samples, 0.5); }

// Interquartile range: the spread reported next to each median.
inline double interquartile_range(const std::vector<double>& samples) {
    return quantile(samples, 0.75) - quantile(samples, 0.25);
}

} // namespace kdop
