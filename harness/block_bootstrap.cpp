#include "harness/block_bootstrap.h"

#include "harness/statistics.h"
#include "images/random.h"

#include <algorithm>
#include <cmath>

namespace kdop {

std::optional<std::vector<std::vector<double>>>
bootstrap_replicates(const std::vector<std::vector<std::vector<double>>>& figures, const BootstrapOptions& o) {
    if (figures.empty() || figures.front().empty() || o.block == 0 || o.replicates == 0) return std::nullopt;
    const std::vector<std::vector<double>>& first = figures.front();
    for (const auto& candidate : figures) {
        if (candidate.size() != first.size()) return std::nullopt;
        for (std::size_t s = 0; s < first.size(); ++s)
            if (candidate[s].size() != first[s].size()) return std::nullopt;
    }
    // One block cannot show how the figure varies: every replicate would be the figure itself.
    for (const auto& sequence : first)
        if (sequence.size() < 2 * o.block) return std::nullopt;

    std::vector<std::vector<double>> replicates(figures.size(), std::vector<double>(o.replicates, 0.0));
    Random random(o.seed);
    std::vector<std::size_t> drawn; // the first frame of each block drawn in one sequence
    for (std::size_t r = 0; r < o.replicates; ++r)
        for (std::size_t s = 0; s < first.size(); ++s) {
            const std::size_t frames = first[s].size(), blocks = (frames + o.block - 1) / o.block;
            drawn.clear();
            for (std::size_t b = 0; b < blocks; ++b) drawn.push_back(o.block * std::size_t(random.next() % blocks));
            for (std::size_t c = 0; c < figures.size(); ++c) {
                double sum = 0;
                std::size_t count = 0;
                for (std::size_t start : drawn)
                    for (std::size_t f = start; f < std::min(start + o.block, frames); ++f, ++count)
                        sum += figures[c][s][f];
                replicates[c][r] += sum / double(count) / double(first.size());
            }
        }
    return replicates;
}

std::size_t history_block(double current_weight) {
    return current_weight > 0 ? std::max<std::size_t>(1, std::size_t(std::ceil(1 / current_weight))) : 1;
}

Interval percentile_interval(const std::vector<double>& replicates, double level) {
    if (replicates.empty()) return {};
    std::vector<double> sorted = replicates;
    std::sort(sorted.begin(), sorted.end());
    return {quantile_of_sorted(sorted, (1 - level) / 2), quantile_of_sorted(sorted, (1 + level) / 2)};
}

Interval difference_interval(const std::vector<double>& a, const std::vector<double>& b, double level) {
    if (a.size() != b.size()) return {};
    std::vector<double> difference(a.size());
    for (std::size_t r = 0; r < a.size(); ++r) difference[r] = a[r] - b[r];
    return percentile_interval(difference, level);
}

} // namespace kdop
