#include "optimize/choose.h"

#include "core/builtin_sets.h"
#include "core/input_files.h"
#include "generator/analytic_cost.h"
#include "generator/axis_set.h"
#include "harness/progress.h"
#include "harness/statistics.h"
#include "temporal/taa_sources.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

namespace kdop {

Recommendation recommend(const std::vector<Candidate>& candidates, std::optional<std::size_t> budget_ops,
                         std::optional<double> target_ghosting) {
    std::optional<std::size_t> best;
    auto better = [&](const Candidate& c, const Candidate& b) {
        if (target_ghosting)
            return c.float_ops < b.float_ops ||
                   (c.float_ops == b.float_ops && c.validation_ghosting < b.validation_ghosting);
        return c.validation_ghosting < b.validation_ghosting ||
               (c.validation_ghosting == b.validation_ghosting && c.float_ops < b.float_ops);
    };
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        const Candidate& c = candidates[i];
        if (std::isnan(c.validation_ghosting)) continue;
        if (target_ghosting && !(c.validation_ghosting <= *target_ghosting)) continue;
        if (!target_ghosting && budget_ops && c.float_ops > *budget_ops) continue;
        if (!best || better(c, candidates[*best])) best = i;
    }
    Recommendation r{best, {}};
    if (!best) {
        r.why = target_ghosting
                    ? fmt::format("no candidate's held-out ghosting reaches the target {:.4g}", *target_ghosting)
                    : fmt::format("no candidate's clip costs at most {} float ops", budget_ops.value_or(0));
        return r;
    }
    const Candidate& c = candidates[*best];
    r.why = target_ghosting
                ? fmt::format("the cheapest candidate ({} float ops) whose held-out ghosting, {:.4f}, reaches the "
                              "target {:.4g}",
                              c.float_ops, c.validation_ghosting, *target_ghosting)
            : budget_ops ? fmt::format("the least held-out ghosting, {:.4f}, of the candidates whose clip costs at "
                                       "most {} float ops (it costs {})",
                                       c.validation_ghosting, *budget_ops, c.float_ops)
                         : fmt::format("the least held-out ghosting, {:.4f}, of every candidate (no budget given; "
                                       "it costs {} float ops)",
                                       c.validation_ghosting, c.float_ops);
    return r;
}

std::vector<std::size_t> pareto_front(const std::vector<Candidate>& candidates) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < candidates.size(); ++i)
        if (!std::isnan(candidates[i].validation_ghosting)) order.push_back(i);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        const Candidate &x = candidates[a], &y = candidates[b];
        return x.float_ops < y.float_ops ||
               (x.float_ops == y.float_ops && x.validation_ghosting < y.validation_ghosting);
    });
    // Cheapest first: each candidate on the front ghosts strictly less than every cheaper one.
    std::vector<std::size_t> front;
    double least = INFINITY;
    for (std::size_t i : order)
        if (candidates[i].validation_ghosting < least) {
            front.push_back(i);
            least = candidates[i].validation_ghosting;
        }
    return front;
}

namespace {

// The sequences, read and checked as kdop taa reads them (taa_sources.h), naming `option`.
Result<std::vector<SequenceFrames>> read_sequences(const Context& context, const std::vector<std::string>& dirs,
                                                   const ChooseOptions& o, std::size_t variants,
                                                   const std::string& option) {
    TaaSourceRequest request;
    request.sequences = dirs;
    request.warmup = o.evaluation.schedule.warmup;
    request.resolve = o.evaluation.resolve;
    request.input_space = o.input_space;
    request.device_flip = !o.evaluation.cpu_flip;
    request.variants = variants;
    request.builtin = false;
    request.option = option;
    auto sources = taa_sources(context, request);
    if (!sources) return std::unexpected(sources.error());
    return std::move(sources->sequences);
}

// Each variant's ghosting on `sequences`: the mean of each sequence's mean; with `per_frame`, every
// measured frame's ghosting (and, in `shimmer`, the mean of the sequences' shimmer).
Result<std::vector<double>> mean_ghosting(TaaEvaluation& evaluation, const std::vector<SequenceFrames>& sequences,
                                          Progress& progress, std::vector<std::vector<double>>* per_frame = nullptr,
                                          std::vector<double>* shimmer = nullptr) {
    const std::size_t variants = evaluation.specs().size();
    std::vector<double> ghosting(variants, 0.0);
    if (shimmer) shimmer->assign(variants, 0.0);
    if (per_frame) per_frame->assign(variants, {});
    EvaluationObserver observer;
    observer.frame = [&](const std::string& source) { progress.advance(source); };
    for (const SequenceFrames& sequence : sequences) {
        auto rows = evaluation.measure(sequence, observer);
        if (!rows) return std::unexpected(rows.error());
        for (const EvaluationRow& row : *rows) {
            ghosting[row.variant] += row.ghosting / double(sequences.size());
            if (shimmer) (*shimmer)[row.variant] += row.shimmer / double(sequences.size());
            if (per_frame)
                for (const FrameFigures& f : row.per_frame)
                    if (!std::isnan(f.ghosting)) (*per_frame)[row.variant].push_back(f.ghosting);
        }
    }
    return ghosting;
}

} // namespace

Result<ChooseResult> choose(const Context& context, const ChooseOptions& o) {
    if (o.validate.empty())
        return usage_fail("choose: give --validate SEQUENCE... held out of the fit: every figure a choice rests on "
                          "is measured on frames the sets were not fitted to, and without them there are none");
    if (o.fit.empty()) return usage_fail("choose: give --fit SEQUENCE... to fit the axis sets to");
    for (const std::string& held : o.validate)
        for (const std::string& fitted : o.fit) {
            std::error_code ec;
            if (std::filesystem::equivalent(held, fitted, ec))
                return usage_fail(fmt::format("--validate {}: also given to --fit; a held-out sequence must not be "
                                              "fitted to",
                                              held));
        }
    if (o.budget_ops && o.target_ghosting)
        return usage_fail("--budget-ops and --target-ghosting: give one rule to choose by");

    // The candidates: a fitted set per axis count, then the built-in sets, each in every mode and
    // neighborhood asked for.
    ChooseResult result;
    std::vector<AxisSet> fitted_sets;
    for (std::size_t axes : o.fit_axes) {
        OptimizeOptions fit;
        fit.input.sequences = o.fit;
        fit.input.input_space = o.input_space;
        fit.input.color_map = o.evaluation.resolve.color_map; // the space the set clips in
        fit.axes = axes;
        fit.name = fmt::format("fitted{}", axes);
        fit.out = (std::filesystem::path(o.out) / (fit.name + ".axes")).string();
        fit.write_out = false;
        fit.seed = o.seed;
        fit.threads = o.threads;
        fit.sample = o.sample;
        fit.accuracy_samples = 0;
        auto ranks = Ranks::world();
        if (!ranks) return std::unexpected(ranks.error());
        auto fitted = optimize(fit, **ranks);
        if (!fitted) return std::unexpected(fitted.error());
        auto set = parse_axis_set(fitted->file, fit.out);
        if (!set) return std::unexpected(set.error());
        fitted_sets.push_back(std::move(*set));
        result.fitted_files.emplace_back(fit.name + ".axes", fitted->file);
    }
    const std::vector<std::string> builtin =
        o.sets.empty() ? std::vector<std::string>(builtin_set_names().begin(), builtin_set_names().end()) : o.sets;
    auto builtin_specs = select_variants(builtin, o.modes, o.neighborhoods, {});
    if (!builtin_specs) return usage_fail("--sets: " + builtin_specs.error().message);
    std::vector<VariantSpec> specs;
    for (const AxisSet& set : fitted_sets)
        for (const VariantSpec& like : *builtin_specs)
            if (like.set.name == builtin_specs->front().set.name) specs.push_back({set, like.mode, like.neighborhood});
    const std::size_t fitted_count = specs.size();
    specs.insert(specs.end(), builtin_specs->begin(), builtin_specs->end());

    auto validate = read_sequences(context, o.validate, o, specs.size(), "--validate");
    if (!validate) return std::unexpected(validate.error());
    auto fit = read_sequences(context, o.fit, o, specs.size(), "--fit");
    if (!fit) return std::unexpected(fit.error());
    // Candidates are judged by their ghosting; a sequence meant only for shimmer has none.
    for (const auto& [option, sequences] : {std::pair{"--validate", &*validate}, std::pair{"--fit", &*fit}})
        for (const SequenceFrames& s : *sequences)
            if (!s.roles().ghosting)
                return usage_fail(fmt::format("{} {}: its sequence.json measures only shimmer, and kdop choose judges "
                                              "candidates by their ghosting",
                                              option, s.sequence().dir.string()));
    for (const SequenceFrames& s : *fit) result.fit_sequences.push_back(s.name());
    for (const SequenceFrames& s : *validate) result.validate_sequences.push_back(s.name());

    auto evaluation = TaaEvaluation::create(context, specs, o.evaluation);
    if (!evaluation) return std::unexpected(evaluation.error());
    std::size_t frames = 0;
    for (const auto* sequences : {&*validate, &*fit})
        for (const SequenceFrames& s : *sequences) frames += s.frame_count();
    Progress progress(fmt::format("TAA of {} candidates on the held-out and fitted sequences,", specs.size()), frames);
    std::vector<std::vector<double>> held_frames;
    std::vector<double> held_shimmer;
    auto held = mean_ghosting(*evaluation, *validate, progress, &held_frames, &held_shimmer);
    if (!held) return std::unexpected(held.error());
    auto in_sample = mean_ghosting(*evaluation, *fit, progress);
    if (!in_sample) return std::unexpected(in_sample.error());

    for (std::size_t v = 0; v < specs.size(); ++v) {
        Candidate c;
        c.key = specs[v].key();
        c.fitted = v < fitted_count;
        c.float_ops = analytic_min_float_ops(specs[v].set, specs[v].mode, specs[v].neighborhood);
        c.fit_ghosting = (*in_sample)[v];
        c.validation_ghosting = (*held)[v];
        c.validation_shimmer = held_shimmer[v];
        c.validation_ghosting_median = quantile(held_frames[v], 0.5);
        c.validation_ghosting_p95 = quantile(held_frames[v], 0.95);
        result.candidates.push_back(std::move(c));
    }
    result.recommendation = recommend(result.candidates, o.budget_ops, o.target_ghosting);
    return result;
}

} // namespace kdop
