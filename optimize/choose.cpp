#include "optimize/choose.h"

#include "bench/cost_table.h"
#include "bench/set_cost.h"
#include "bench/timing.h"
#include "core/builtin_sets.h"
#include "core/input_files.h"
#include "core/read_file.h"
#include "generator/analytic_cost.h"
#include "generator/axis_set.h"
#include "generator/spirv_cost.h"
#include "harness/gnuplot.h"
#include "harness/progress.h"
#include "harness/scratch_directory.h"
#include "harness/statistics.h"
#include "harness/variant_catalog.h"
#include "optimize/fit_compare.h"
#include "optimize/fit_data.h"
#include "optimize/fit_strategies.h"
#include "temporal/taa_sources.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>

namespace kdop {

std::optional<ChooseConflict> check(const ChooseOptions& o) {
    using Kind = ChooseConflict::Kind;
    if (o.validate.empty() && o.holdout == 0) return ChooseConflict{Kind::nothing_held_out, {}};
    if (!o.validate.empty() && o.holdout > 0) return ChooseConflict{Kind::held_out_twice, {}};
    if (o.fit.empty()) return ChooseConflict{Kind::nothing_fitted, {}};
    for (const std::string& held : o.validate)
        for (const std::string& fitted : o.fit) {
            std::error_code ec;
            if (std::filesystem::equivalent(held, fitted, ec)) return ChooseConflict{Kind::fitted_and_held_out, held};
        }
    if (int(o.budget_ops.has_value()) + int(o.budget_ms.has_value()) + int(o.target_ghosting.has_value()) > 1)
        return ChooseConflict{Kind::two_rules, {}};
    return std::nullopt;
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
    // No output may land on a sequence's file: refused now, not when the set is written.
    for (const SequenceFrames& s : sources->sequences)
        if (auto ok = check_outside(s.sequence(), o.out, "--out"); !ok) return std::unexpected(ok.error());
    return std::move(sources->sequences);
}

// Each variant's figures over the frames of `sequences` that a filter accepts (all measured
// frames without one), by metric: the mean over the sequences of each one's mean (what taa.csv
// holds, the same sums in the same order), and every counted frame's value by sequence, for the
// median, the 95th percentile and the bootstrap.
struct Figures {
    std::vector<std::vector<double>> means;                            // [variant][metric]
    std::vector<std::vector<std::vector<std::vector<double>>>> frames; // [variant][metric][sequence][frame]

    std::vector<double> all_frames(std::size_t variant, std::size_t metric) const {
        std::vector<double> all;
        for (const std::vector<double>& sequence : frames[variant][metric])
            all.insert(all.end(), sequence.begin(), sequence.end());
        return all;
    }
    // One metric's frames of every variant, [variant][sequence][frame]: what the bootstrap draws from.
    std::vector<std::vector<std::vector<double>>> of_metric(std::size_t metric) const {
        std::vector<std::vector<std::vector<double>>> out;
        for (const auto& variant : frames) out.push_back(variant[metric]);
        return out;
    }
};
using FrameFilter = std::function<bool(std::size_t frame)>;

// Mean of `values`, NaN for none: a sequence's figure over the counted frames.
double mean_of(const std::vector<double>& values) {
    double sum = 0;
    for (double v : values) sum += v;
    return values.empty() ? NAN : sum / double(values.size());
}

// Measures every variant on `sequences` once, and gives the figures of each filter's frames.
Result<std::vector<Figures>> measure_figures(TaaEvaluation& evaluation, const std::vector<SequenceFrames>& sequences,
                                             const std::vector<FrameFilter>& filters, Progress& progress) {
    const std::size_t variants = evaluation.specs().size(), metrics = evaluation.metrics().size();
    const Figures empty{std::vector<std::vector<double>>(variants, std::vector<double>(metrics, 0.0)),
                        std::vector<std::vector<std::vector<std::vector<double>>>>(
                            variants, std::vector<std::vector<std::vector<double>>>(metrics))};
    std::vector<Figures> figures(filters.size(), empty);
    EvaluationObserver observer;
    observer.frame = [&](const std::string& source) -> Result<void> {
        progress.advance(source);
        return {};
    };
    for (const SequenceFrames& sequence : sequences) {
        auto rows = evaluation.measure(sequence, observer);
        if (!rows) return std::unexpected(rows.error());
        for (const EvaluationRow& row : *rows)
            for (std::size_t f = 0; f < filters.size(); ++f)
                for (std::size_t m = 0; m < metrics; ++m) {
                    std::vector<double> values;
                    for (const FrameFigures& frame : row.per_frame)
                        if ((!filters[f] || filters[f](frame.index)) && !std::isnan(frame.value(m)))
                            values.push_back(frame.value(m));
                    Figures& into = figures[f];
                    into.means[row.variant][m] += mean_of(values) / double(sequences.size());
                    into.frames[row.variant][m].push_back(std::move(values));
                }
    }
    return figures;
}

// Every rank's candidates' figures, on every rank: rank r measured candidates [first, end) of
// ranks.share(variants) into `mine` (indexed from its first); the whole is what one rank measuring
// every candidate gets, each candidate's figures being its own history's alone. Two all-gathers:
// each candidate's means and per-sequence frame counts, then its frames' values.
Figures gather_figures(const Ranks& ranks, const Figures& mine, std::size_t variants, std::size_t metrics,
                       std::size_t sequences) {
    const auto [first, end] = ranks.share(variants);
    const std::size_t head = metrics * (1 + sequences); // the means, then the counts by (metric, sequence)
    std::vector<double> heads(variants * head);
    for (std::size_t v = first; v < end; ++v)
        for (std::size_t m = 0; m < metrics; ++m) {
            heads[v * head + m] = mine.means[v - first][m];
            for (std::size_t s = 0; s < sequences; ++s)
                heads[v * head + metrics + m * sequences + s] = double(mine.frames[v - first][m][s].size());
        }
    ranks.all_gather(heads, std::vector<std::size_t>(variants, head));
    std::vector<std::size_t> lengths(variants, 0), offsets(variants + 1, 0);
    for (std::size_t v = 0; v < variants; ++v) {
        for (std::size_t i = metrics; i < head; ++i) lengths[v] += std::size_t(heads[v * head + i]);
        offsets[v + 1] = offsets[v] + lengths[v];
    }
    std::vector<double> values(offsets.back());
    for (std::size_t v = first; v < end; ++v) {
        std::size_t at = offsets[v];
        for (const auto& metric : mine.frames[v - first])
            for (const std::vector<double>& sequence : metric)
                at = std::size_t(std::copy(sequence.begin(), sequence.end(), values.begin() + at) - values.begin());
    }
    ranks.all_gather(values, lengths);
    Figures all{std::vector<std::vector<double>>(variants, std::vector<double>(metrics)),
                std::vector<std::vector<std::vector<std::vector<double>>>>(
                    variants, std::vector<std::vector<std::vector<double>>>(metrics))};
    for (std::size_t v = 0; v < variants; ++v) {
        std::size_t at = offsets[v];
        for (std::size_t m = 0; m < metrics; ++m) {
            all.means[v][m] = heads[v * head + m];
            for (std::size_t s = 0; s < sequences; ++s) {
                const auto count = std::size_t(heads[v * head + metrics + m * sequences + s]);
                all.frames[v][m].emplace_back(values.begin() + at, values.begin() + at + count);
                at += count;
            }
        }
    }
    return all;
}

// The candidates' rectification passes timed on the device (bench/timing.h, as kdop taa times
// them), interleaved, and the float ops of each pass's SPIR-V as the generator counts them (what
// kdop gen and kdop bench print: the same catalog, the same modules). `sets` are --sets' names and
// files; the fitted sets are known to the catalog through their files, written to a scratch folder
// for it.
struct TimedCandidates {
    bench::TimingRun timing;
    std::vector<std::size_t> float_ops;
};
Result<TimedCandidates> time_candidates(const Context& context, const std::vector<VariantSpec>& specs,
                                        const std::vector<std::pair<std::string, std::string>>& fitted_files,
                                        const std::vector<std::string>& sets, std::uint32_t width, std::uint32_t height,
                                        unsigned rounds) {
    ScratchDirectory scratch("kdop-choose");
    if (scratch.path.empty()) return fail("cannot create a scratch folder for the fitted sets (is TMPDIR writable?)");
    std::vector<std::string> known = sets; // built-in names and the user's files, as --sets gave them
    for (const auto& [name, text] : fitted_files) {
        if (auto ok = write_text(scratch.path / name, text); !ok) return std::unexpected(ok.error());
        known.push_back((scratch.path / name).string());
    }
    auto catalog = VariantCatalog::create(known);
    if (!catalog) return std::unexpected(catalog.error());
    std::vector<VariantKey> keys;
    for (const VariantSpec& spec : specs) keys.push_back(spec.key());
    auto rectifiers = catalog->find_all(keys, "--sets");
    if (!rectifiers) return std::unexpected(rectifiers.error());
    TimedCandidates timed;
    for (const Variant* v : *rectifiers)
        timed.float_ops.push_back(count_float_ops({v->spirv, v->spirv_word_count}).total());
    Progress progress(fmt::format("timing {} candidates on {},", specs.size(), context.device_name()), rounds);
    auto timing = bench::time_interleaved(context, *rectifiers, width, height, rounds, progress);
    if (!timing) return std::unexpected(timing.error());
    timed.timing = std::move(*timing);
    return timed;
}

// What every rank checks and reads before the fit: the candidates that are not fitted, the
// sequences, and what is held out.
struct Plan {
    Holdout holdout;
    std::vector<std::string> builtin;       // --sets, or every built-in set
    std::vector<VariantSpec> builtin_specs; // each in every mode and neighborhood asked for
    std::vector<VariantSpec> per_set;       // one set's modes and neighborhoods, for the fitted sets
    std::vector<SequenceFrames> fit, validate;
};

// Every candidate's set has a name of its own, or the timing's catalog refuses the second after
// every fit has run: a count given twice to --fit-axes, a --sets file whose set is named as a
// fitted one (fitted4) or as a built-in one. Refused before any work.
Result<void> check_set_names(const ChooseOptions& o, const Plan& plan) {
    for (auto axes = o.fit_axes.begin(); axes != o.fit_axes.end(); ++axes)
        if (std::find(o.fit_axes.begin(), axes, *axes) != axes)
            return usage_fail(
                fmt::format("--fit-axes: {} is given twice; each count fits one set, fitted{}", *axes, *axes));
    if (auto catalog = VariantCatalog::create(plan.builtin); !catalog) return usage_fail(catalog.error().message);
    for (std::size_t axes : o.fit_axes)
        for (const VariantSpec& spec : plan.builtin_specs)
            if (spec.set.name == fmt::format("fitted{}", axes))
                return usage_fail(fmt::format("--sets {}: its set is named '{}', as the set --fit-axes {} fits is; "
                                              "rename it (its name: line) or leave {} out of --fit-axes",
                                              spec.set.origin, spec.set.name, axes, axes));
    return {};
}

// Each --sets file that is not built in, read whole for kdop.manifest (GivenSetFile), by set name.
Result<std::map<std::string, GivenSetFile>> given_set_files(const ChooseOptions& o, const Plan& plan) {
    std::map<std::string, GivenSetFile> files;
    for (const std::string& given : plan.builtin) {
        if (is_builtin_set(given)) continue;
        const auto spec =
            std::ranges::find(plan.builtin_specs, given, [](const VariantSpec& s) { return s.set.origin; });
        if (spec == plan.builtin_specs.end()) continue; // select_variants read every one: cannot happen
        auto text = read_input_file(given);
        if (!text) return fail(fmt::format("--sets: {}", text.error().message));
        const std::filesystem::path copy = std::filesystem::path(o.out) / (spec->set.name + ".axes");
        files[spec->set.name] = {given, std::move(*text), same_file(given, copy)};
    }
    return files;
}

// The set files kdop choose writes in --out (fitted<N>.axes, and the copy of a --sets file) must
// not replace a file this run reads, which the write would refuse only after the work: a --sets
// file left in --out under another set's name, say.
Result<void> check_set_outputs(const ChooseOptions& o, const ChooseResult& result) {
    std::vector<std::string> names;
    for (std::size_t axes : o.fit_axes) names.push_back(fmt::format("fitted{}.axes", axes));
    std::vector<std::filesystem::path> inputs;
    for (const auto& [set, file] : result.given_files) {
        inputs.emplace_back(file.given);
        if (!file.in_place) names.push_back(set + ".axes");
    }
    for (const std::string& name : names) {
        const std::filesystem::path output = std::filesystem::path(o.out) / name;
        std::optional<std::filesystem::path> input = noted_input_at(output);
        for (const std::filesystem::path& given : inputs)
            if (!input && same_file(output, given)) input = given;
        if (input)
            return usage_fail(fmt::format("--out {}: kdop choose writes {} there, and that file is {}, an input of "
                                          "this run; kdop never writes over an input, so give another --out or move "
                                          "the file",
                                          o.out, name, input->string()));
    }
    return {};
}

Result<Plan> plan_candidates(const Context& context, const ChooseOptions& o, ChooseResult& result) {
    Plan plan;
    plan.holdout = {o.holdout, o.evaluation.schedule.warmup};
    // The candidates: a fitted set per axis count, then the built-in sets, each in every mode and
    // neighborhood asked for. Their count is known before the fit, so everything is checked first.
    plan.builtin =
        o.sets.empty() ? std::vector<std::string>(builtin_set_names().begin(), builtin_set_names().end()) : o.sets;
    auto builtin_specs = select_variants(plan.builtin, o.modes, o.neighborhoods, {}, kCommandDefaults);
    if (!builtin_specs) return usage_fail("--sets: " + builtin_specs.error().message);
    plan.builtin_specs = std::move(*builtin_specs);
    for (const VariantSpec& spec : plan.builtin_specs)
        if (spec.set.name == plan.builtin_specs.front().set.name) plan.per_set.push_back(spec);
    const std::size_t candidates = plan.builtin_specs.size() + o.fit_axes.size() * plan.per_set.size();
    if (auto ok = check_set_names(o, plan); !ok) return std::unexpected(ok.error());
    if (auto given = given_set_files(o, plan); given)
        result.given_files = std::move(*given);
    else
        return std::unexpected(given.error());

    auto fit = read_sequences(context, o.fit, o, candidates, "--fit");
    if (!fit) return std::unexpected(fit.error());
    auto validate = read_sequences(context, o.validate, o, candidates, "--validate");
    if (!validate) return std::unexpected(validate.error());
    // Candidates are judged by their ghosting; a sequence meant only for shimmer has none.
    for (const auto& [option, sequences] : {std::pair{"--validate", &*validate}, std::pair{"--fit", &*fit}})
        for (const SequenceFrames& s : *sequences)
            if (!s.roles().ghosting)
                return usage_fail(fmt::format("{} {}: its sequence.json measures only shimmer, and kdop choose judges "
                                              "candidates by their ghosting",
                                              option, s.sequence().dir.string()));
    // A held-out sequence made of the fit's own frame files (a copy of hard links, `cp -al`, or of
    // links) holds nothing out, whatever its folder is called.
    std::map<FileIdentity, std::filesystem::path> fitted_frames;
    for (const SequenceFrames& s : *fit)
        for (const SequenceFrame& frame : s.sequence().frames)
            if (auto id = file_identity(frame.color)) fitted_frames.emplace(*id, frame.color);
    for (const SequenceFrames& s : *validate)
        for (const SequenceFrame& frame : s.sequence().frames)
            if (auto id = file_identity(frame.color); id && fitted_frames.contains(*id))
                return usage_fail(fmt::format("--validate {}: its frame {} is the same file as --fit's {} (a hard "
                                              "link or a link); a held-out sequence must not hold the frames fitted "
                                              "to",
                                              s.sequence().dir.string(), frame.color.string(),
                                              fitted_frames.at(*id).string()));
    // Every figure in one FLIP mode: an LDR sequence's ghosting (LDR-FLIP) and an HDR one's
    // (HDR-FLIP) are on different scales, and a gap between them would read as overfitting.
    const SequenceFrames* first = !fit->empty() ? &fit->front() : nullptr;
    for (const auto& [option, sequences] : {std::pair{"--fit", &*fit}, std::pair{"--validate", &*validate}})
        for (const SequenceFrames& s : *sequences)
            if (first && s.color_range() != first->color_range()) {
                auto mode = [](const SequenceFrames& f) {
                    return f.color_range() == ColorRange::hdr ? "HDR, measured in HDR-FLIP"
                                                              : "LDR, measured in LDR-FLIP";
                };
                return usage_fail(fmt::format("{} {}: its sequence.json's color range is {}, and --fit {} is {}; "
                                              "ghosting in LDR-FLIP and in HDR-FLIP are on different scales, so "
                                              "held-out and fitted figures of both cannot be compared: give "
                                              "sequences of one range",
                                              option, s.sequence().dir.string(), mode(s),
                                              first->sequence().dir.string(), mode(*first)));
            }
    result.range = first ? first->color_range() : ColorRange::ldr;
    result.upscaled =
        std::ranges::any_of(*fit, &FrameSource::upscales) || std::ranges::any_of(*validate, &FrameSource::upscales);
    result.metrics = o.evaluation.metrics;
    // Held-out blocks: every fit sequence must have a frame in one.
    const Holdout& holdout = plan.holdout;
    if (holdout.block > 0)
        for (const SequenceFrames& s : *fit)
            if (s.frame_count() <= holdout.warmup + holdout.block)
                return usage_fail(fmt::format("--holdout {}: {} has {} frames, so after the warmup of {} no frame is "
                                              "held out (the second block of {} would start at frame {})",
                                              holdout.block, s.sequence().dir.string(), s.frame_count(), holdout.warmup,
                                              holdout.block, holdout.warmup + holdout.block));
    for (const SequenceFrames& s : *fit) result.fit_sequences.push_back(s.name());
    for (const SequenceFrames& s : *validate) result.validate_sequences.push_back(s.name());
    result.held_out =
        holdout.block > 0
            ? fmt::format("every other block of {} frames after the warm-up of the fitted sequences, the second, the "
                          "fourth and so on (frames {} to {}, {} to {}, ...)",
                          holdout.block, holdout.warmup + holdout.block, holdout.warmup + 2 * holdout.block - 1,
                          holdout.warmup + 3 * holdout.block, holdout.warmup + 4 * holdout.block - 1)
            : fmt::format("the sequences given to --validate ({})", fmt::join(result.validate_sequences, ", "));
    plan.fit = std::move(*fit), plan.validate = std::move(*validate);
    if (auto ok = check_set_outputs(o, result); !ok) return std::unexpected(ok.error());
    return plan;
}

// One set per --fit-axes count, fitted as kdop optimize fits a fixed axis count to the fit
// sequences (read once, shared over the ranks), each in the modes and neighborhoods of the built-in
// candidates; their files, as kdop optimize writes them, into `result`.
Result<std::vector<VariantSpec>> fit_candidates(const ChooseOptions& o, const Plan& plan, const Ranks& ranks,
                                                ChooseResult& result) {
    const unsigned threads = rank_threads(o.threads);
    const ColorMap& space = o.evaluation.resolve.color_map; // the space the set clips in
    auto data = read_fit_data(
        {{{}, o.fit, 1, plan.holdout, o.input_space, space}, Neighborhood::n9, o.sample, o.seed, std::nullopt, ""},
        ranks);
    if (!data) return std::unexpected(data.error());
    const std::string objective = fit_objective(*data, Neighborhood::n9, space);
    std::vector<VariantSpec> specs;
    for (std::size_t axes : o.fit_axes) {
        const FitResult fit = fit_axis_count({data->fitted_to(), {axes, false, o.seed, threads, 0, 0, {}}}, axes);
        FitRecord record;
        record.name = fmt::format("fitted{}", axes);
        record.seed = o.seed;
        record.stopped_early = fit.stopped_early;
        record.color_map = space;
        record.objective = objective;
        record.sets = compared_sets(&*data->neighborhoods, fit.axes, threads);
        record.score = record.sets[0].score;
        if (o.sample)
            record.notes.push_back(fmt::format("Sampled: {}.", sample_line(*data, o.seed, fit.score, record.score)));
        auto file = fitted_set_text(record, fit.axes);
        if (!file) return fail(file.error().message);
        const std::string name = record.name + ".axes";
        auto set = parse_axis_set(*file, (std::filesystem::path(o.out) / name).string());
        if (!set) return std::unexpected(set.error());
        for (const VariantSpec& like : plan.per_set) specs.push_back({*set, like.mode, like.neighborhood});
        result.fitted_files.emplace_back(name, std::move(*file));
    }
    return specs;
}

// This rank's share of the candidates measured: with --validate every measured frame of those
// sequences, then of the fitted ones; with --holdout the fitted sequences once, their held-out
// frames and the others. A rank with no candidate measures nothing.
struct MeasuredShare {
    Figures held, in_sample;
};
Result<MeasuredShare> measure_candidates(const Context& context, const ChooseOptions& o, const Plan& plan,
                                         const std::vector<VariantSpec>& specs, const Ranks& ranks) {
    const auto [first, end] = ranks.share(specs.size());
    const std::vector<VariantSpec> mine(specs.begin() + std::ptrdiff_t(first), specs.begin() + std::ptrdiff_t(end));
    if (mine.empty()) return MeasuredShare{};
    auto evaluation = TaaEvaluation::create(context, mine, o.evaluation);
    if (!evaluation) return std::unexpected(evaluation.error());
    std::size_t frames = 0;
    for (const auto* sequences : {&plan.validate, &plan.fit})
        for (const SequenceFrames& s : *sequences) frames += s.frame_count();
    Progress progress(fmt::format("TAA of {} candidates on the held-out and fitted frames,", specs.size()), frames);
    if (plan.holdout.block == 0) {
        auto on_validate = measure_figures(*evaluation, plan.validate, {nullptr}, progress);
        if (!on_validate) return std::unexpected(on_validate.error());
        auto on_fit = measure_figures(*evaluation, plan.fit, {nullptr}, progress);
        if (!on_fit) return std::unexpected(on_fit.error());
        return MeasuredShare{std::move(on_validate->front()), std::move(on_fit->front())};
    }
    const Holdout& holdout = plan.holdout;
    auto split = measure_figures(
        *evaluation, plan.fit,
        {[&](std::size_t i) { return holdout.held_out(i); }, [&](std::size_t i) { return !holdout.held_out(i); }},
        progress);
    if (!split) return std::unexpected(split.error());
    return MeasuredShare{std::move((*split)[0]), std::move((*split)[1])};
}

} // namespace

Result<ChooseResult> choose(const Context& context, const ChooseOptions& o, const Ranks& ranks) {
    // --lavapipe-cost runs kdop-dispatch-probe, built beside kdop, under callgrind: checked first.
    std::optional<ScratchDirectory> callgrind_scratch;
    if (o.lavapipe_cost) callgrind_scratch.emplace("kdop-choose-callgrind");
    const bench::CallgrindSetup callgrind{
        std::filesystem::read_symlink("/proc/self/exe").parent_path() / "kdop-dispatch-probe",
        callgrind_scratch ? callgrind_scratch->path : std::filesystem::path(), 256, ""};

    ChooseResult result;
    auto plan = check(o) ? fail("kdop choose: options that check() refuses") : plan_candidates(context, o, result);
    if (plan && o.lavapipe_cost && (callgrind.scratch.empty() || !std::filesystem::exists(callgrind.probe)))
        plan = fail(fmt::format("--lavapipe-cost: needs {} (built with kdop) and a scratch directory",
                                callgrind.probe.string()));
    // A rank that cannot read a sequence stops them all here, before the fit's collectives.
    if (auto ok = ranks.agree(plan ? Result<void>{} : std::unexpected(plan.error())); !ok)
        return std::unexpected(ok.error());

    auto specs = stop_ranks_on_lost_frame<std::vector<VariantSpec>>(
        ranks, [&] { return fit_candidates(o, *plan, ranks, result); });
    if (!specs) return std::unexpected(specs.error());
    // The fit is every rank's, and so is the measuring, each rank its share of the candidates (each
    // candidate's figures are its own history's, whichever others share the pass); the timings and
    // the outputs are rank 0's.
    const std::size_t fitted_count = specs->size();
    specs->insert(specs->end(), plan->builtin_specs.begin(), plan->builtin_specs.end());
    const Holdout& holdout = plan->holdout;
    const std::vector<SequenceFrames>&fit = plan->fit, &validate = plan->validate;
    auto measured = measure_candidates(context, o, *plan, *specs, ranks);
    if (auto ok = ranks.agree(measured ? Result<void>{} : std::unexpected(measured.error())); !ok)
        return std::unexpected(ok.error());
    const std::size_t metric_count = o.evaluation.metrics.size();
    const Figures held = gather_figures(ranks, measured->held, specs->size(), metric_count,
                                        holdout.block == 0 ? validate.size() : fit.size());
    const Figures in_sample = gather_figures(ranks, measured->in_sample, specs->size(), metric_count, fit.size());
    if (!ranks.is_root()) return result;
    result.ranks = ranks.size();

    // Each candidate's rectification pass timed as kdop taa times it, at the held-out frames' size.
    const SequenceFrames& sized = validate.empty() ? fit.front() : validate.front();
    auto timed = time_candidates(context, *specs, result.fitted_files, plan->builtin, sized.width(), sized.height(),
                                 o.timing_rounds);
    if (!timed) return std::unexpected(timed.error());

    // With --lavapipe-cost, each clip's instructions beyond the gather (varclip has no such count).
    std::vector<double> instructions(specs->size(), NAN);
    if (o.lavapipe_cost) {
        const auto clips = std::ranges::count_if(*specs, [](const VariantSpec& s) { return s.mode == Mode::clip; });
        Progress progress("counting lavapipe instructions of", 2 * std::size_t(clips));
        for (std::size_t v = 0; v < specs->size(); ++v)
            if ((*specs)[v].mode == Mode::clip) {
                auto counted =
                    bench::marginal_clip_instructions((*specs)[v].set, (*specs)[v].neighborhood, callgrind, progress);
                if (!counted)
                    return fail(
                        fmt::format("--lavapipe-cost: {}: {}", variant_name((*specs)[v]), counted.error().message));
                instructions[v] = *counted;
            }
    }

    // Each held-out ghosting's interval: blocks of frames that share their history, drawn alike for
    // every candidate (harness/block_bootstrap.h).
    result.bootstrap.block = history_block(o.evaluation.resolve.current_weight);
    result.bootstrap.seed = o.seed, result.bootstrap.level = kChoiceLevel;
    const auto replicates = bootstrap_replicates(held.of_metric(kGhosting), result.bootstrap);
    for (std::size_t v = 0; v < specs->size(); ++v) {
        const VariantSpec& spec = (*specs)[v];
        Candidate c;
        c.key = spec.key();
        c.fitted = v < fitted_count;
        c.rank = ranks.owner(v, specs->size());
        c.float_ops = timed->float_ops[v];
        c.analytic_ops = analytic_min_float_ops(spec.set, spec.mode, spec.neighborhood);
        c.range = result.range;
        const std::vector<double>& ms = timed->timing.ms[v];
        c.ms = median(ms), c.ms_q1 = quantile(ms, 0.25), c.ms_q3 = quantile(ms, 0.75);
        c.lavapipe_instructions = instructions[v];
        for (std::size_t m = 0; m < result.metrics.size(); ++m) {
            const std::vector<double> frames = held.all_frames(v, m);
            c.figures.push_back({.fit = in_sample.means[v][m],
                                 .held_out = held.means[v][m],
                                 .held_out_median = quantile(frames, 0.5),
                                 .held_out_p95 = quantile(frames, 0.95)});
        }
        if (replicates) {
            c.replicates = (*replicates)[v];
            c.interval = percentile_interval(c.replicates, kChoiceLevel);
        }
        result.candidates.push_back(std::move(c));
    }
    result.recommendation = recommend(result.candidates, {o.budget_ops, o.budget_ms}, o.target_ghosting);
    mark_noise(result.candidates, result.recommendation);
    return result;
}

} // namespace kdop
