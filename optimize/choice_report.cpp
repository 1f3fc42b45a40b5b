#include "optimize/choice_report.h"

#include "core/escaped_text.h"
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

Table candidates_table(const std::vector<Candidate>& candidates) {
    const DeclaredColumns<Candidate> columns =
        variant_key_columns<Candidate>([](const Candidate& c) -> const VariantKey& { return c.key; }) +
        DeclaredColumns<Candidate>{
            {{"fitted", "", Shown::flag, 0}, [](const Candidate& c) { return Value(c.fitted); }},
            {{"float_ops", "", Shown::integer, 0, "float ops"},
             [](const Candidate& c) { return Value(std::int64_t(c.float_ops)); }},
        } +
        time_columns<Candidate>(&Candidate::ms, &Candidate::ms_q1, &Candidate::ms_q3) +
        DeclaredColumns<Candidate>{
            {{"lavapipe_instr", "instr/px", Shown::fixed, 1, "lavapipe instr/px beyond the gather"},
             [](const Candidate& c) { return maybe(c.lavapipe_instructions); }},
            {{"fit_ghosting", "FLIP", Shown::fixed, 4, "ghosting on the fit frames"},
             [](const Candidate& c) { return maybe(c.fit_ghosting); }},
            {{"validation_ghosting", "FLIP", Shown::fixed, 4, "held-out ghosting"},
             [](const Candidate& c) { return maybe(c.validation_ghosting); }},
            {{"validation_ghosting_median", "FLIP", Shown::fixed, 4, "held-out median"},
             [](const Candidate& c) { return maybe(c.validation_ghosting_median); }},
            {{"validation_ghosting_p95", "FLIP", Shown::fixed, 4, "held-out p95"},
             [](const Candidate& c) { return maybe(c.validation_ghosting_p95); }},
            {{"validation_shimmer", "FLIP", Shown::fixed, 4, "held-out shimmer"},
             [](const Candidate& c) { return maybe(c.validation_shimmer); }},
        };
    return declared_table<Candidate>(columns, candidates);
}

std::string choice_markdown(const ChooseResult& r, const ChooseOptions& o, const RunMetadata& run, bool chart) {
    const auto names = [](const std::vector<std::string>& list) {
        return fmt::format("{}", fmt::join(list | std::views::transform(markdown_text), ", "));
    };
    std::string md = "# kdop choose: the variant to ship\n\n";
    md += fmt::format("Axis sets of {} axes were fitted to {} (the mean k-DOP volume over their frames' neighborhoods, "
                      "the held-out frames left out, in {} colors), then every candidate was measured as `kdop taa "
                      "--sequence` measures it ({}). **Held-out ghosting** is measured on {}: the mean over the "
                      "sequences of each one's mean FLIP over those of its measured frames (after {} frames of "
                      "warm-up), and its median and 95th percentile are over all those frames together. **Ghosting on "
                      "the fit frames** is the same figure on the frames fitted to: what a fitted set's own figures "
                      "would have claimed. **Float ops** are the hardened clip's, as the generator counts them; **ms** "
                      "the median device time of its rectification pass at the held-out frames' size, with its "
                      "quartiles over interleaved rounds, as kdop taa times it.\n\n",
                      fmt::join(o.fit_axes, ", "), names(r.fit_sequences), to_string(o.evaluation.resolve.color_map),
                      describe(o.evaluation.resolve), markdown_text(r.held_out), o.evaluation.schedule.warmup);

    // Least held-out ghosting first.
    std::vector<Candidate> sorted = r.candidates;
    std::stable_sort(sorted.begin(), sorted.end(), [](const Candidate& a, const Candidate& b) {
        return a.validation_ghosting < b.validation_ghosting;
    });
    md += "## Every candidate, least held-out ghosting first\n\n" + candidates_table(sorted).markdown() + "\n";

    md += "## The Pareto front of held-out ghosting against cost\n\nNo other candidate is as cheap and ghosts as "
          "little; cheapest first:\n\n";
    for (std::size_t i : pareto_front(r.candidates)) {
        const Candidate& c = r.candidates[i];
        md += fmt::format("- {}: {} float ops, held-out ghosting {:.4f}{}\n", markdown_text(c.key.name()), c.float_ops,
                          c.validation_ghosting, c.fitted ? " (fitted)" : "");
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
        md += fmt::format("**{}**: {}. kdop.manifest selects it{}.\n\n", markdown_text(c.key.name()), rec.why,
                          c.fitted                       ? fmt::format(", with its set's file, {}.axes", c.key.set)
                          : given == r.given_files.end() ? ""
                          : given->second.in_place
                              ? fmt::format(", with its set's file, {}.axes, given to --sets", c.key.set)
                              : fmt::format(", with its set's file, {}.axes, a copy of {} (given to --sets)", c.key.set,
                                            markdown_text(given->second.given)));
    }
    // Whether fitting paid off out of sample: the best fitted candidate against the best built-in one.
    const Candidate *best_fitted = nullptr, *best_builtin = nullptr;
    for (const Candidate& c : r.candidates) {
        const Candidate*& best = c.fitted ? best_fitted : best_builtin;
        if (!std::isnan(c.validation_ghosting) && (!best || c.validation_ghosting < best->validation_ghosting))
            best = &c;
    }
    if (best_fitted && best_builtin) {
        if (best_builtin->validation_ghosting <= best_fitted->validation_ghosting)
            md += fmt::format("**The fitted sets lost on the held-out frames**: the best built-in candidate, {}, "
                              "ghosts {:.4f} there, the best fitted one, {}, {:.4f} (on the frames it was fitted to, "
                              "{:.4f}).\n\n",
                              markdown_text(best_builtin->key.name()), best_builtin->validation_ghosting,
                              markdown_text(best_fitted->key.name()), best_fitted->validation_ghosting,
                              best_fitted->fit_ghosting);
        else
            md += fmt::format("The best fitted candidate, {}, ghosts {:.4f} on the held-out frames, less than the best "
                              "built-in one, {}, at {:.4f}.\n\n",
                              markdown_text(best_fitted->key.name()), best_fitted->validation_ghosting,
                              markdown_text(best_builtin->key.name()), best_builtin->validation_ghosting);
    }
    return md + metadata_markdown(run);
}

std::string choice_manifest(const ChooseResult& r) {
    if (!r.recommendation.chosen) return {};
    const Candidate& c = r.candidates[*r.recommendation.chosen];
    std::string text = "# kdop choose's recommendation (choice.md says why).\n";
    if (c.fitted || r.given_files.count(c.key.set)) text += fmt::format("set: {}.axes\n", c.key.set);
    return text + c.key.name() + "\n";
}

Result<ChooseResult> run_choose(const Context& context, const ChooseOptions& options, const Ranks& ranks,
                                OutputSet& outputs) {
    auto chosen = choose(context, options, ranks);
    if (!chosen || !ranks.is_root()) return chosen;
    const RunMetadata run = describe_run(context);
    // A chart that fails costs the chart, not the run.
    bool charted = false;
    if (charts_available(options.chart)) {
        ScratchDirectory scratch("kdop-choose");
        auto chart = scratch.path.empty() ? Result<std::vector<OutputFile>>(fail("no scratch directory"))
                                          : choice_chart(*chosen, scratch.path, outputs.dir());
        if (chart)
            outputs.add(std::move(*chart)), charted = true;
        else
            warn_no_charts(chart.error().message);
    }
    outputs.add_table("candidates", candidates_table(chosen->candidates), run);
    outputs.add("choice.md", choice_markdown(*chosen, options, run, charted));
    for (const auto& [name, text] : chosen->fitted_files) outputs.add(name, text);
    if (const std::string manifest = choice_manifest(*chosen); !manifest.empty()) {
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
