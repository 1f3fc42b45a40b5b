#include "optimize/choice_report.h"

#include "core/escaped_text.h"
#include "core/shown_text.h"
#include "generator/manifest.h"
#include "harness/declared_table.h"
#include "harness/gnuplot.h"
#include "harness/scratch_directory.h"
#include "optimize/choice_chart.h"
#include "temporal/resolve_options.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <ranges>

namespace kdop {

namespace {

const char* flip_mode(ColorRange range) { return range == ColorRange::hdr ? "HDR-FLIP" : "LDR-FLIP"; }

// The columns of each metric's figures: the ranking metric's (ghosting's) on the fit frames and
// held out, with its interval, noise flag, median and p95; every other one measured held out.
DeclaredColumns<Candidate> figure_columns(const Metrics& metrics, ColorRange range) {
    DeclaredColumns<Candidate> columns;
    auto figure = [](std::size_t m, double CandidateFigure::*field) {
        return [m, field](const Candidate& c) { return maybe(m < c.figures.size() ? c.figures[m].*field : NAN); };
    };
    for (std::size_t m : ranking_first(metrics)) {
        const Metric& metric = metrics[m];
        if (!metric.measured) continue;
        // Every FLIP figure's unit is the mode it was measured in, and a column says it too (taa.csv's).
        const std::string unit = metric.flip ? flip_mode(range) : metric.unit, &n = metric.name;
        const int d = metric.digits;
        if (m != ranking_first(metrics).front()) {
            columns.push_back(
                {{"validation_" + n, unit, Shown::fixed, d, "held-out " + n}, figure(m, &CandidateFigure::held_out)});
            continue;
        }
        columns.push_back(
            {{"fit_" + n, unit, Shown::fixed, d, n + " on the fit frames"}, figure(m, &CandidateFigure::fit)});
        columns.push_back(
            {{"validation_" + n, unit, Shown::fixed, d, "held-out " + n}, figure(m, &CandidateFigure::held_out)});
        columns.push_back({{"validation_" + n + "_low", unit, Shown::fixed, d,
                            fmt::format("{:.0f}% interval from", 100 * kChoiceLevel)},
                           [](const Candidate& c) { return maybe(c.interval.low); }});
        columns.push_back({{"validation_" + n + "_high", unit, Shown::fixed, d, "to"},
                           [](const Candidate& c) { return maybe(c.interval.high); }});
        columns.push_back({{n + "_noise", "", Shown::flag, 0, "held-out " + n + " within noise of the recommended"},
                           [](const Candidate& c) { return c.within_noise ? Value(*c.within_noise) : Value(); }});
        columns.push_back({{"validation_" + n + "_median", unit, Shown::fixed, d, "held-out median"},
                           figure(m, &CandidateFigure::held_out_median)});
        columns.push_back({{"validation_" + n + "_p95", unit, Shown::fixed, d, "held-out p95"},
                           figure(m, &CandidateFigure::held_out_p95)});
    }
    return columns;
}

} // namespace

Table candidates_table(const std::vector<Candidate>& candidates, const Metrics& metrics) {
    const ColorRange range = candidates.empty() ? ColorRange::ldr : candidates.front().range;
    const DeclaredColumns<Candidate> columns =
        variant_key_columns<Candidate>([](const Candidate& c) -> const VariantKey& { return c.key; }) +
        DeclaredColumns<Candidate>{
            {{"fitted", "", Shown::flag, 0}, [](const Candidate& c) { return Value(c.fitted); }},
            {{"float_ops", "", Shown::integer, 0, "float ops (generator)"},
             [](const Candidate& c) { return Value(std::int64_t(c.float_ops)); }},
            {{"analytic_min_ops", "", Shown::integer, 0, "analytic min"},
             [](const Candidate& c) { return Value(std::int64_t(c.analytic_ops)); }},
        } +
        time_columns<Candidate>(&Candidate::ms, &Candidate::ms_q1, &Candidate::ms_q3) +
        DeclaredColumns<Candidate>{
            {{"ms_noise", "", Shown::flag, 0, "ms within noise of the fastest"},
             [](const Candidate& c) { return std::isfinite(c.ms) ? Value(c.ms_noise) : Value(); }},
            {{"lavapipe_instr", "instr/px", Shown::fixed, 1, "lavapipe instr/px beyond the gather"},
             [](const Candidate& c) { return maybe(c.lavapipe_instructions); }},
        } +
        figure_columns(metrics, range) +
        DeclaredColumns<Candidate>{
            {{"flip", "", Shown::text, 0, "measured in"},
             [](const Candidate& c) { return Value(std::string(flip_mode(c.range))); }},
        };
    return declared_table<Candidate>(columns, candidates);
}

namespace {

// How the intervals were drawn, or why there are none.
std::string bootstrap_paragraph(const ChooseResult& r) {
    const BootstrapOptions& b = r.bootstrap;
    const bool drawn =
        std::any_of(r.candidates.begin(), r.candidates.end(), [](const Candidate& c) { return c.interval.known(); });
    if (!drawn)
        return fmt::format("The held-out frames are too few for intervals: each held-out sequence needs at least two "
                           "bootstrap blocks of {} frames, so nothing here says which differences are noise.\n\n",
                           b.block);
    return fmt::format(
        "**The interval** beside each held-out ghosting is a {:.0f}% block-bootstrap interval: each held-out "
        "sequence's frames are cut into blocks of {} consecutive frames (ceil(1 / current weight), about the frames "
        "one "
        "history averages, so frames of one block share their history), and {} replicates draw as many blocks with "
        "replacement (seed {}, `--seed`); the interval spans the middle {:.0f}% of the replicates' figure. Every "
        "candidate is drawn on the same blocks, so a candidate is *within noise* of the recommended one "
        "(ghosting_noise; of the least held-out ghosting where none is recommended) where the interval of their "
        "difference holds 0: the held-out frames do not tell the two apart.\n\n",
        100 * b.level, b.block, b.replicates, b.seed, 100 * b.level);
}

// Every setting the figures were measured with: the variant's, the resolve's, FLIP's.
// The resolve the candidates were measured through: the options', upscaling where the sequences did.
ResolveSettings measured_resolve(const ChooseResult& r, const ChooseOptions& o) {
    ResolveOptions resolve = o.evaluation.resolve;
    resolve.upscale = r.upscaled;
    return resolve_settings(resolve);
}

// Which rank measured which candidates, under mpirun; nothing for one rank.
std::string ranks_line(const ChooseResult& r) {
    if (r.ranks <= 1) return {};
    std::string line = fmt::format("The candidates were measured over {} ranks (mpirun), each its share; the "
                                   "timings are rank 0's:",
                                   r.ranks);
    for (int rank = 0; rank < r.ranks; ++rank) {
        std::vector<std::string> names;
        for (const Candidate& c : r.candidates)
            if (c.rank == rank) names.push_back(markdown_text(c.key.name()));
        line += fmt::format(" rank {} {}{}", rank, names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", ")),
                            rank + 1 < r.ranks ? ";" : ".\n\n");
    }
    return line;
}

// The settings section's head: its title, and the recommended variant's mode and neighborhood.
std::string settings_head(const ChooseResult& r) {
    std::string md = "## What the figures were measured with\n\n| setting | value |\n|---|---|\n";
    if (r.recommendation.chosen) {
        const Candidate& c = r.candidates[*r.recommendation.chosen];
        md += fmt::format("| mode (recommended) | {} |\n| neighborhood (recommended) | {} |\n", to_string(c.key.mode),
                          to_string(c.key.neighborhood));
    }
    return md;
}

// The same, measured through a renderer's own resolve (--resolve): only what kdop gave it.
std::string own_resolve_section(const ChooseResult& r, const ChooseOptions& o, const OwnResolve& own) {
    std::string md = settings_head(r);
    md += fmt::format("| resolve | {} (--resolve), bound by {} |\n| gamma, where its map takes it | {} |\n"
                      "| current weight, where its map takes it | {} |\n| FLIP | {} at {:.1f} pixels per degree |\n"
                      "| warm-up | {} frames |\n\n",
                      markdown_code(own.label()), markdown_code(own.bindings.file), o.evaluation.resolve.gamma,
                      o.evaluation.resolve.current_weight, r.range == ColorRange::hdr ? "HDR-FLIP" : "LDR-FLIP",
                      o.evaluation.ppd, o.evaluation.schedule.warmup);
    md += ranks_line(r);
    if (r.recommendation.chosen)
        md += "kdop.manifest names the resolve in a comment and records no resolve settings: the figures are those "
              "of your resolve, as your build makes it, with kdop's variant in it.\n\n";
    return md;
}

std::string settings_section(const ChooseResult& r, const ChooseOptions& o) {
    if (o.evaluation.own_resolve) return own_resolve_section(r, o, *o.evaluation.own_resolve);
    const ResolveSettings settings = measured_resolve(r, o);
    std::string md = settings_head(r);
    md += fmt::format("| gamma (the variance clip's width; varclip only) | {} |\n| current weight | {} |\n"
                      "| color map | {} |\n| history filter | {} |\n| motion dilation | {} |\n"
                      "| FLIP | {} at {:.1f} pixels per degree |\n| warm-up | {} frames |\n\n",
                      settings.gamma, settings.current_weight, markdown_text(color_map_text(settings)),
                      to_string(settings.history_filter), settings.dilate_motion ? "yes" : "no",
                      r.range == ColorRange::hdr ? "HDR-FLIP" : "LDR-FLIP", o.evaluation.ppd,
                      o.evaluation.schedule.warmup);
    md += ranks_line(r);
    if (settings.upscaling)
        md += fmt::format("The resolve upscaled the sequences' frames: filter {}, the clip's samples {}, box scale "
                          "{}.\n\n",
                          to_string(settings.upscale_filter), to_string(settings.sample_distance),
                          to_string(settings.box_scale));
    if (r.recommendation.chosen)
        md += "kdop.manifest records the resolve's settings beside the variant (its gamma:, current-weight:, "
              "color-map:, history-filter: and dilate-motion: lines, and its upscale- lines where it upscaled), and "
              "kdop_add_variants(MANIFEST) gives them to "
              "the build as `resolve_settings` in the registry's header and \"resolve\" in its JSON "
              "(docs/embedding.md): a resolve built otherwise may not see these figures.\n\n";
    return md;
}

} // namespace

std::string choice_markdown(const ChooseResult& r, const ChooseOptions& o, const RunMetadata& run, bool chart) {
    const auto names = [](const std::vector<std::string>& list) {
        return fmt::format("{}", fmt::join(list | std::views::transform(markdown_text), ", "));
    };
    const char* flip = r.range == ColorRange::hdr ? "HDR-FLIP" : "LDR-FLIP";
    std::string md = "# kdop choose: the variant to ship\n\n";
    md += fmt::format(
        "Axis sets of {} axes were fitted to {} (the mean k-DOP volume over their frames' neighborhoods, the held-out "
        "frames left out, in {} colors), then every candidate was measured as `kdop taa --sequence` measures it ({}). "
        "**Every ghosting and shimmer here is {}**: the sequences are {}, and kdop choose refuses sequences of two "
        "ranges, whose figures are on different scales. **Held-out ghosting** is measured on {}: the mean over the "
        "sequences of each one's mean FLIP over those of its measured frames (after {} frames of warm-up), and its "
        "median and 95th percentile are over all those frames together. **Ghosting on the fit frames** is the same "
        "figure on the frames fitted to: what a fitted set's own figures would have claimed. **Float ops** are those "
        "of the candidate's compute shader as the generator counts them in its optimized SPIR-V: the count `kdop gen` "
        "and `kdop bench` print, which `--budget-ops` is held against; **analytic min** is the analytic lower bound "
        "of its clip (kdop bench's column of that name), a few below. **ms** is the median device time of its "
        "rectification pass at the held-out frames' size, with its quartiles over interleaved rounds, as kdop taa "
        "times it, and *within noise* of the fastest (ms_noise) where it differs from the fastest's by no more than "
        "the larger interquartile range of the two.\n\n",
        fmt::join(o.fit_axes, ", "), names(r.fit_sequences), to_string(o.evaluation.resolve.color_map),
        describe(o.evaluation.resolve), flip, r.range == ColorRange::hdr ? "HDR" : "LDR", markdown_text(r.held_out),
        o.evaluation.schedule.warmup);
    md += bootstrap_paragraph(r);
    // Least held-out ghosting first.
    std::vector<Candidate> sorted = r.candidates;
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const Candidate& a, const Candidate& b) { return a.ranked() < b.ranked(); });
    md +=
        "## Every candidate, least held-out ghosting first\n\n" + candidates_table(sorted, r.metrics).markdown() + "\n";

    md += "## The Pareto front of held-out ghosting against cost\n\nNo other candidate is as cheap and ghosts as "
          "little; cheapest first:\n\n";
    for (std::size_t i : pareto_front(r.candidates)) {
        const Candidate& c = r.candidates[i];
        md += fmt::format("- {}: {} float ops, held-out ghosting {:.4f}{}\n", markdown_text(c.key.name()), c.float_ops,
                          c.ranked(), c.fitted ? " (fitted)" : "");
    }

    if (chart)
        md += "\nEvery candidate's held-out ghosting against its cost, the front joined and the recommendation "
              "ringed: ![held-out ghosting against float ops](choice.png)\n";
    md += "\n## The recommendation\n\n";
    const Recommendation& rec = r.recommendation;
    if (!rec.chosen) {
        md += fmt::format("None: {}. kdop.manifest is not written.\n\n", rec.why);
    } else {
        const Candidate& c = r.candidates[*rec.chosen];
        const auto given = r.given_files.find(c.key.set);
        md += fmt::format("**{}**: {}. kdop.manifest selects it{}.\n\n{}\n\n", markdown_text(c.key.name()), rec.why,
                          c.fitted                       ? fmt::format(", with its set's file, {}.axes", c.key.set)
                          : given == r.given_files.end() ? ""
                          : given->second.in_place
                              ? fmt::format(", with its set's file, {}.axes, given to --sets", c.key.set)
                              : fmt::format(", with its set's file, {}.axes, a copy of {} (given to --sets)", c.key.set,
                                            markdown_text(given->second.given)),
                          markdown_text(rec.noise));
    }
    // Whether fitting paid off out of sample: the best fitted candidate against the best built-in one.
    const Candidate *best_fitted = nullptr, *best_builtin = nullptr;
    for (const Candidate& c : r.candidates) {
        const Candidate*& best = c.fitted ? best_fitted : best_builtin;
        if (!std::isnan(c.ranked()) && (!best || c.ranked() < best->ranked())) best = &c;
    }
    if (best_fitted && best_builtin) {
        if (best_builtin->ranked() <= best_fitted->ranked())
            md += fmt::format("**The fitted sets lost on the held-out frames**: the best built-in candidate, {}, "
                              "ghosts {:.4f} there, the best fitted one, {}, {:.4f} (on the frames it was fitted to, "
                              "{:.4f}).\n\n",
                              markdown_text(best_builtin->key.name()), best_builtin->ranked(),
                              markdown_text(best_fitted->key.name()), best_fitted->ranked(), best_fitted->ranked_fit());
        else
            md += fmt::format("The best fitted candidate, {}, ghosts {:.4f} on the held-out frames, less than the best "
                              "built-in one, {}, at {:.4f}.\n\n",
                              markdown_text(best_fitted->key.name()), best_fitted->ranked(),
                              markdown_text(best_builtin->key.name()), best_builtin->ranked());
    }
    return md + settings_section(r, o) + metadata_markdown(run);
}

std::string choice_manifest(const ChooseResult& r, const ChooseOptions& o) {
    if (!r.recommendation.chosen) return {};
    const Candidate& c = r.candidates[*r.recommendation.chosen];
    std::string text = "# kdop choose's recommendation (choice.md says why), and the TAA resolve it was measured\n"
                       "# with: build the resolve with these (kdop_add_variants declares them as resolve_settings).\n";
    if (o.evaluation.own_resolve)
        text += fmt::format("# Measured through your own resolve, {} (kdop choose --resolve), with a current weight\n"
                            "# of {:g} and a gamma of {:g} where its map takes them.\n",
                            one_line_text(o.evaluation.own_resolve->label()), o.evaluation.resolve.current_weight,
                            o.evaluation.resolve.gamma);
    else
        text += resolve_lines(measured_resolve(r, o));
    if (c.fitted || r.given_files.count(c.key.set)) text += fmt::format("set: {}.axes\n", c.key.set);
    return text + c.key.name() + "\n";
}

Result<ChooseResult> run_choose(const Context& context, const ChooseOptions& options, const Ranks& ranks,
                                OutputSet& outputs) {
    auto chosen = choose(context, options, ranks);
    if (!chosen || !ranks.is_root()) return chosen;
    RunMetadata run = describe_run(context);
    if (options.evaluation.own_resolve) run.resolve = options.evaluation.own_resolve->label();
    // A chart that fails costs the chart, not the run.
    bool charted = false;
    if (charts_available(options.chart)) {
        ScratchDirectory scratch("kdop-choose");
        auto chart = scratch.path.empty() ? Result<std::vector<OutputFile>>(fail("no scratch directory"))
                                          : choice_chart(*chosen, options, scratch.path, outputs.dir());
        if (chart)
            outputs.add(std::move(*chart)), charted = true;
        else
            warn_no_charts(chart.error().message);
    }
    outputs.add_table("candidates", candidates_table(chosen->candidates, chosen->metrics), run);
    outputs.add("choice.md", choice_markdown(*chosen, options, run, charted));
    for (const auto& [name, text] : chosen->fitted_files) outputs.add(name, text);
    if (const std::string manifest = choice_manifest(*chosen, options); !manifest.empty()) {
        outputs.add("kdop.manifest", manifest);
        // A --sets file's set recommended: its copy beside the manifest, which reads no other folder.
        const std::string& set = chosen->candidates[*chosen->recommendation.chosen].key.set;
        if (auto given = chosen->given_files.find(set); given != chosen->given_files.end() && !given->second.in_place)
            outputs.add(set + ".axes", given->second.text);
    }
    if (auto ok = outputs.write(); !ok) return std::unexpected(ok.error());
    return chosen;
}

} // namespace kdop
