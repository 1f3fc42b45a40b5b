#include "optimize/optimize.h"

#include "core/write_files.h"
#include "optimize/fit_check.h"
#include "optimize/fit_compare.h"
#include "optimize/fit_data.h"
#include "optimize/fit_strategies.h"
#include "optimize/set_evaluator.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <optional>
#include <utility>

namespace kdop {
namespace {

using Objective = OptimizeOptions::Objective;

// What the strategies found: the set, their tables, and with the distance objective where the
// descent went and the pixels it descended on.
struct FoundSet {
    FitResult fit;
    std::vector<std::string> table;
    std::optional<RefinedFit> refined;
    std::vector<ClipSample> samples;
};

// The strategies the options ask for, in turn: a fixed axis count or the fewest that reach a
// target, then components pinned at 0, or the descent on the distance.
Result<FoundSet> find_set(const OptimizeOptions& o, const FitData& data, SequenceGhosting* ghosting, const Ranks& ranks,
                          const OptimizeRows& on_row) {
    const FitSearch search = fit_search(o, data.fitted_to());
    SetEvaluator evaluator(o, ghosting, ranks);
    if (auto ok = evaluator.ready(); !ok) return std::unexpected(ok.error());
    FitTable table{{}, on_row};
    Result<FitResult> fit = o.target || o.target_ghosting ? fit_to_target(o, search, evaluator, table)
                                                          : Result<FitResult>(fit_axis_count(search, o.axes));
    if (fit && o.max_nonzero) fit = fit_sparser_set(o, search, evaluator, std::move(*fit), table);
    if (!fit) return std::unexpected(fit.error());
    FoundSet found{std::move(*fit), std::move(table.rows), {}, {}};
    if (o.objective == Objective::distance) {
        // Read while the neighborhoods are held: the distance objective needs both.
        auto samples = read_distance_samples(o, data, ranks);
        if (!samples) return fail(samples.error().message);
        found.samples = std::move(*samples);
        found.refined = refine_on_distance(search, found.fit, found.samples);
        found.fit.axes = found.refined->fit.axes;
        found.fit.stopped_early |= found.refined->fit.stopped_early;
    }
    return found;
}

// The file's lines between the objective and the distance: the sample, the descent, the table.
std::vector<std::string> fit_notes(const OptimizeOptions& o, const OptimizeResult& r,
                                   const std::vector<std::string>& table) {
    std::vector<std::string> notes;
    if (o.sample) notes.push_back(fmt::format("Sampled: {}.", r.sample_line));
    if (!r.refined_line.empty()) notes.push_back(fmt::format("Refined: {}.", r.refined_line));
    if (o.target) notes.push_back(fmt::format("The fewest axes that reach --target {:.6g}:", *o.target));
    if (o.target_ghosting)
        notes.push_back(fmt::format("The fewest axes whose ghosting reaches --target-ghosting {:.6g} on {} (kdop taa "
                                    "--sequence's measure, warmup {}, LDR- or HDR-FLIP as each sequence says):",
                                    *o.target_ghosting, fmt::join(o.input.sequences, ", "), o.warmup));
    if (o.max_nonzero)
        notes.push_back(fmt::format("Components pinned at 0 one by one, to at most {}:", *o.max_nonzero));
    for (const std::string& row : table) notes.push_back("  " + row);
    return notes;
}

// The found set beside the built-in ones (volume on every neighborhood, then the distance), and the
// file that says so, written to options.out by rank 0.
Result<OptimizeResult> compare_and_write(const OptimizeOptions& o, FitData& data, FoundSet found, const Ranks& ranks) {
    const bool by_distance = o.objective == Objective::distance;
    const std::string objective = fit_objective(data, o.neighborhood, o.input.color_map);
    OptimizeResult r;
    r.sets = compared_sets(data.neighborhoods ? &*data.neighborhoods : nullptr, found.fit.axes, o.threads);
    const double sample_score = std::exchange(found.fit.score, r.sets[0].score);
    if (o.sample) r.sample_line = sample_line(data, o.seed, sample_score, found.fit.score);
    r.own_frames = data.neighborhoods ? data.neighborhoods->own_frames() : 0;
    r.held_frames = data.neighborhoods ? data.neighborhoods->held_frames() : 0;
    r.frames = data.inputs.frames.size();
    // The distance's pixels read after the neighborhoods are freed, so the peak stays within the memory held.
    data.neighborhoods.reset(), data.sampled.reset();
    if (!by_distance && !o.sphere && o.accuracy_samples > 0) {
        auto samples = read_distance_samples(o, data, ranks);
        if (!samples) return fail(samples.error().message);
        found.samples = std::move(*samples);
    }
    r.distance_measure = distance_measure(o, found.samples.size());
    add_distances(r.sets, found.samples);
    r.closer_warning = closer_warning(r.sets);
    r.fitted_objective = by_distance ? fmt::format("{}, then the mean distance to the ideal clip on {} sampled pixels",
                                                   objective, found.samples.size())
                                     : objective;
    r.fitted_score = by_distance ? found.refined->fit.score : found.fit.score;
    if (found.refined) r.refined_line = found.refined->line;
    const FitRecord record{set_name(o),
                           o.seed,
                           o.starts,
                           o.iterations,
                           o.force_rgb,
                           found.fit.stopped_early,
                           o.sphere ? std::nullopt : std::optional(o.input.color_map),
                           r.fitted_objective,
                           r.fitted_score,
                           fit_notes(o, r, found.table),
                           r.distance_measure,
                           r.sets,
                           r.closer_warning};
    auto file = fitted_set_text(record, found.fit.axes);
    if (!file) return fail(file.error().message);
    // The same file on every rank: rank 0 writes it.
    if (ranks.is_root())
        if (auto ok = write_files_atomically({{o.out, *file}}); !ok) return fail(ok.error().message);
    r.file = std::move(*file);
    r.fit = std::move(found.fit);
    return r;
}

Result<OptimizeResult> run(const OptimizeOptions& o, const Ranks& ranks, const OptimizeRows& on_row) {
    if (check(o) || check_ranks(o, ranks.size())) return fail("kdop optimize: options that check() refuses");
    // With a ghosting target, each row's set resolved over the sequences as kdop taa --sequence
    // does, on rank 0: opened before the frames are read, so a sequence the resolve cannot take
    // (a warmup beyond its frames) is refused before any work, not after the reading.
    std::unique_ptr<SequenceGhosting> ghosting;
    auto open = [&]() -> Result<void> {
        if (!o.target_ghosting) return {};
        auto opened = open_ghosting(o, ranks);
        if (!opened) return std::unexpected(opened.error());
        ghosting = std::move(*opened);
        return {};
    };
    auto data = o.sphere ? Result<FitData>(FitData{})
                         : read_fit_data({o.input, o.neighborhood, o.sample, o.seed, o.memory, o.out}, ranks, open);
    if (!data) return std::unexpected(data.error());
    auto found = find_set(o, *data, ghosting.get(), ranks, on_row);
    if (!found) return std::unexpected(found.error());
    return compare_and_write(o, *data, std::move(*found), ranks);
}

} // namespace

Result<OptimizeResult> optimize(const OptimizeOptions& options, const Ranks& ranks, const OptimizeRows& on_row) {
    OptimizeOptions o = options;
    o.threads = rank_threads(o.threads);
    return stop_ranks_on_lost_frame<OptimizeResult>(ranks, [&] { return run(o, ranks, on_row); });
}

} // namespace kdop
