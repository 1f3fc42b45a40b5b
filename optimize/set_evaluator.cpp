#include "optimize/set_evaluator.h"

#include "bench/set_cost.h"
#include "fit/fitted_set.h"
#include "generator/analytic_cost.h"
#include "harness/progress.h"
#include "optimize/fit_check.h"

#include <fmt/format.h>

namespace kdop {

Result<std::unique_ptr<SequenceGhosting>> open_ghosting(const OptimizeOptions& o, const Ranks& ranks) {
    std::unique_ptr<SequenceGhosting> ghosting;
    Result<void> opened;
    if (ranks.is_root()) {
        ResolveOptions resolve = o.resolve;
        resolve.color_map = o.input.color_map; // the space the set is fitted in is the one it clips in
        auto created = SequenceGhosting::create(o.input.sequences, o.input.input_space, resolve, o.warmup);
        if (created)
            ghosting = std::move(*created);
        else
            opened = std::unexpected(created.error());
    }
    if (auto ok = ranks.agree(opened); !ok) return std::unexpected(ok.error());
    return ghosting;
}

SetEvaluator::SetEvaluator(const OptimizeOptions& o, SequenceGhosting* ghosting, const Ranks& ranks)
    : name_(set_name(o)), out_(o.out), color_map_(o.sphere ? std::nullopt : std::optional(o.input.color_map)),
      shape_(o.neighborhood), lavapipe_cost_(o.lavapipe_cost), sequences_(o.input.sequences.size()),
      ghosting_(ghosting), ranks_(ranks),
      probe_(std::filesystem::read_symlink("/proc/self/exe").parent_path() / "kdop-dispatch-probe") {
    if (lavapipe_cost_) scratch_.emplace("kdop-optimize");
}

Result<void> SetEvaluator::ready() const {
    if (lavapipe_cost_ && (scratch_->path.empty() || !std::filesystem::exists(probe_)))
        return fail(
            fmt::format("--lavapipe-cost: needs {} (built with kdop) and a scratch directory", probe_.string()));
    return {};
}

Result<AxisSet> SetEvaluator::axis_set(std::span<const glm::dvec3> axes) const {
    auto text = fitted_set_file({name_, "-", {}, color_map_}, axes);
    if (!text) return std::unexpected(text.error());
    return parse_axis_set(*text, out_);
}

Result<ClipCost> SetEvaluator::cost(std::span<const glm::dvec3> axes) const {
    auto set = axis_set(axes);
    if (!set) return std::unexpected(set.error());
    ClipCost cost{analytic_min_float_ops(*set, Mode::clip, shape_), std::nullopt};
    if (!lavapipe_cost_) return cost;
    Progress progress("counting lavapipe instructions", 2);
    const bench::CallgrindSetup callgrind{probe_, scratch_->path, 256, ""};
    auto instructions = bench::marginal_clip_instructions(*set, shape_, callgrind, progress);
    if (!instructions) return std::unexpected(instructions.error());
    cost.lavapipe_instructions = *instructions;
    return cost;
}

Result<std::vector<std::vector<double>>> SetEvaluator::figures(std::span<const glm::dvec3> axes) const {
    // Flat, sequence after sequence, for the broadcast.
    std::vector<double> flat(sequences_ * metrics_.size(), NAN);
    Result<void> measured;
    if (ranks_.is_root()) {
        Progress progress("measuring the sequences", 1);
        auto set = axis_set(axes);
        auto m = set ? ghosting_->measure(*set, shape_) : std::unexpected(set.error());
        if (m)
            for (std::size_t i = 0; i < m->size(); ++i)
                for (std::size_t metric = 0; metric < metrics_.size(); ++metric)
                    flat[i * metrics_.size() + metric] = (*m)[i].mean(metric);
        else
            measured = std::unexpected(m.error());
    }
    if (auto ok = ranks_.agree(measured); !ok) return std::unexpected(ok.error());
    ranks_.broadcast(flat);
    std::vector<std::vector<double>> figures;
    for (auto sequence = flat.begin(); sequence != flat.end(); sequence += std::ptrdiff_t(metrics_.size()))
        figures.emplace_back(sequence, sequence + std::ptrdiff_t(metrics_.size()));
    return figures;
}

} // namespace kdop
