#include "temporal/taa_intervals.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

namespace kdop {
namespace {

// One row's measured frames of `figure`, by sequence in the order first met (a kdop scene's row has
// a shimmer sequence and a ghosting one; each figure is measured on one of them).
std::vector<std::vector<double>> frames_of(const TaaRow& row, const std::vector<TaaFrameRow>& frames,
                                           std::size_t metric) {
    std::vector<std::pair<std::string, std::vector<double>>> by_sequence;
    for (const TaaFrameRow& f : frames) {
        if (f.scene != row.scene || !(f.key == row.key) || std::isnan(f.value(metric))) continue;
        auto at = std::ranges::find(by_sequence, f.sequence, [](const auto& s) { return s.first; });
        if (at == by_sequence.end()) at = by_sequence.insert(by_sequence.end(), {f.sequence, {}});
        at->second.push_back(f.value(metric));
    }
    std::vector<std::vector<double>> out;
    for (auto& [sequence, values] : by_sequence) out.push_back(std::move(values));
    return out;
}

} // namespace

void add_intervals(std::vector<TaaRow>& rows, const std::vector<TaaFrameRow>& frames, std::size_t metrics,
                   const BootstrapOptions& options) {
    std::vector<std::string> scenes;
    for (const TaaRow& r : rows)
        if (std::ranges::find(scenes, r.scene) == scenes.end()) scenes.push_back(r.scene);
    for (const std::string& scene : scenes) {
        std::vector<TaaRow*> in_scene;
        for (TaaRow& r : rows)
            if (r.scene == scene) in_scene.push_back(&r);
        for (std::size_t metric = 0; metric < metrics; ++metric) {
            std::vector<std::vector<std::vector<double>>> figures;
            bool any = false; // a metric not measured here has no frames to draw from
            for (const TaaRow* r : in_scene) {
                figures.push_back(frames_of(*r, frames, metric));
                any = any || !figures.back().empty();
            }
            if (!any) continue;
            const auto replicates = bootstrap_replicates(figures, options);
            if (!replicates) continue;
            for (std::size_t v = 0; v < in_scene.size(); ++v)
                if (metric < in_scene[v]->figures.size())
                    in_scene[v]->figures[metric].interval = percentile_interval((*replicates)[v], options.level);
            if (metric != kGhosting) continue;
            // Within noise of the least ghosting in the scene: their paired difference's interval holds 0.
            std::optional<std::size_t> best;
            for (std::size_t v = 0; v < in_scene.size(); ++v) {
                const double ghosting = in_scene[v]->mean(kGhosting);
                if (!std::isnan(ghosting) && (!best || ghosting < in_scene[*best]->mean(kGhosting))) best = v;
            }
            for (std::size_t v = 0; best && v < in_scene.size(); ++v)
                in_scene[v]->within_noise =
                    difference_interval((*replicates)[v], (*replicates)[*best], options.level).holds(0);
        }
    }
}

} // namespace kdop
