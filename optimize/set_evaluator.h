// What an axis set a fit found would cost and leave, as the tables of kdop optimize's strategies
// show it: the float ops of its hardened clip (with lavapipe_cost, lavapipe's instructions per
// pixel too, by callgrind) and, with a ghosting target, its figures on each sequence as kdop taa
// --sequence measures them (on rank 0, the figures broadcast to every rank).
#pragma once

#include "core/color_map.h"
#include "core/result.h"
#include "generator/axis_set.h"
#include "harness/ranks.h"
#include "harness/scratch_directory.h"
#include "optimize/optimize.h"
#include "optimize/optimize_tables.h"
#include "temporal/sequence_ghosting.h"

#include <glm/vec3.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace kdop {

// The sequences opened for a ghosting target's measurement, on rank 0 (nullptr on the others): a
// sequence the resolve cannot take (warmup beyond its frames) stops every rank, before any work.
Result<std::unique_ptr<SequenceGhosting>> open_ghosting(const OptimizeOptions& options, const Ranks& ranks);

class SetEvaluator {
public:
    // `ghosting`: open_ghosting's, or nullptr without a ghosting target; kept by the caller.
    SetEvaluator(const OptimizeOptions& options, SequenceGhosting* ghosting, const Ranks& ranks);
    SetEvaluator(const SetEvaluator&) = delete;
    SetEvaluator& operator=(const SetEvaluator&) = delete;

    // With lavapipe_cost: refused where kdop-dispatch-probe (built beside kdop) or a scratch folder is missing.
    Result<void> ready() const;

    // `axes` as the set the file will hold: what the generator costs and the resolve runs.
    Result<AxisSet> axis_set(std::span<const glm::dvec3> axes) const;
    Result<ClipCost> cost(std::span<const glm::dvec3> axes) const;
    // What figures() measures: kdop taa's default metrics.
    const Metrics& metrics() const { return metrics_; }
    // Each sequence's figures in turn, by metric (NaN where not measured); the same on every rank.
    Result<std::vector<std::vector<double>>> figures(std::span<const glm::dvec3> axes) const;

private:
    std::string name_, out_;
    std::optional<ColorMap> color_map_; // none around the sphere: a set for any space
    Neighborhood shape_;
    bool lavapipe_cost_;
    std::size_t sequences_;
    SequenceGhosting* ghosting_;
    Metrics metrics_ = default_metrics(); // SequenceGhosting's too
    const Ranks& ranks_;
    std::optional<ScratchDirectory> scratch_; // callgrind's files, with lavapipe_cost
    std::filesystem::path probe_;
};

} // namespace kdop
