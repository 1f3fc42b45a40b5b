// Spearman's rank correlation: how alike two orderings of the same items are (1: the same order,
// -1: reversed), for comparing kdop's figures with a paper's whatever their scales. Ties share the
// mean of the ranks they span, and the coefficient is Pearson's correlation of the ranks, so it
// stays exact with ties.
#pragma once

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace kdop {

// Ranks from 1 (smallest), ties given the mean of the ranks they span.
inline std::vector<double> fractional_ranks(const std::vector<double>& values) {
    std::vector<std::size_t> order(values.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
    std::vector<double> ranks(values.size());
    for (std::size_t i = 0; i < order.size();) {
        std::size_t j = i;
        while (j + 1 < order.size() && values[order[j + 1]] == values[order[i]]) ++j;
        for (std::size_t k = i; k <= j; ++k) ranks[order[k]] = double(i + j) / 2 + 1;
        i = j + 1;
    }
    return ranks;
}

// Spearman's rho of two equally long lists; NaN when either has fewer than two items or all its
// values equal.
inline double spearman(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size() || a.size() < 2) return NAN;
    const std::vector<double> ra = fractional_ranks(a), rb = fractional_ranks(b);
    const double mean = double(a.size() + 1) / 2; // of ranks 1..n, ties or not
    double ab = 0, aa = 0, bb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        ab += (ra[i] - mean) * (rb[i] - mean);
        aa += (ra[i] - mean) * (ra[i] - mean);
        bb += (rb[i] - mean) * (rb[i] - mean);
    }
    if (aa == 0 || bb == 0) return NAN;
    return ab / std::sqrt(aa * bb);
}

} // namespace kdop
