// kdop choose: fit axis sets to some sequences, judge them and the built-in sets on others held
// out, and write the recommendation with the manifest the build takes (optimize/choose.h).
#include "cli/commands.h"

#include "cli/input_space_option.h"
#include "cli/number_option.h"
#include "cli/own_resolve_option.h"
#include "cli/resolve_option.h"
#include "core/shown_text.h"
#include "generator/selection_options.h"
#include "harness/output_set.h"
#include "harness/ranks.h"
#include "optimize/choice_report.h"
#include "sequence/sequence_corpus.h"

#include <fmt/format.h>

#include <iostream>
#include <memory>

namespace kdop::cli {
namespace {

// A conflict of the options (ChooseConflict), named by the flags that gave them.
std::string conflict_message(const ChooseConflict& conflict) {
    using Kind = ChooseConflict::Kind;
    switch (conflict.kind) {
    case Kind::nothing_held_out:
        return "choose: give --validate SEQUENCE... or --holdout FRAMES: every figure a choice rests on is measured "
               "on frames the sets were not fitted to, and without either there are none";
    case Kind::held_out_twice:
        return "--validate and --holdout: hold out either whole sequences or blocks of frames, not both";
    case Kind::nothing_fitted: return "choose: give --fit SEQUENCE... to fit the axis sets to";
    case Kind::fitted_and_held_out:
        return fmt::format("--validate {}: also given to --fit; a held-out sequence must not be fitted to",
                           conflict.sequence);
    case Kind::two_rules: return "--budget-ops, --budget-ms and --target-ghosting: give one rule to choose by";
    }
    return "";
}

} // namespace

Action add_choose_command(CLI::App& app) {
    struct Options {
        ChooseOptions run;
        OwnResolveOptions own_resolve;
        std::string device;
        double ppd = 0;
    };
    auto o = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand(
        "choose", "Fit axis sets to some frame sequences, measure them and the built-in sets on other sequences held "
                  "out of the fit, as `kdop taa --sequence` measures, and recommend the variant to ship: the least "
                  "held-out ghosting within a cost budget, or the cheapest that meets a ghosting target; writes "
                  "candidates.csv (and JSON), choice.md and its chart, the fitted .axes files and kdop.manifest");
    cmd->add_option("--fit", o->run.fit,
                    "Frame sequences to fit the axis sets to: each a sequence's folder, a folder of sequences or a "
                    "list file (docs/taa.md, \"Many sequences\")")
        ->required()
        ->check(CLI::ExistingPath);
    cmd->add_option("--validate", o->run.validate,
                    "Frame sequences held out of the fit, that every candidate is judged on (this or --holdout: "
                    "nothing is judged on the frames it was fitted to), given as --fit's are")
        ->check(CLI::ExistingPath);
    cmd->add_option("--holdout", o->run.holdout,
                    "Instead of --validate: hold out of the fit every other block of this many frames of the --fit "
                    "sequences after the warmup (the second, the fourth, ...), and judge on those")
        ->check(whole_number(1, 100000))
        ->excludes("--validate");
    cmd->add_option("--fit-axes", o->run.fit_axes, "Axis counts to fit, one set each [default: 4 8 16]")
        ->check(whole_number(3, 32));
    cmd->add_option(
           "--sets", o->run.sets,
           "Other sets among the candidates: built-in names or .axes files (a file's set, recommended, is copied "
           "beside kdop.manifest as <set>.axes) [default: the six built-in sets]")
        ->check(SelectionOptions::axis_set_name());
    cmd->add_option("--modes", o->run.modes,
                    "clip and/or varclip [default: " + default_modes_text(kCommandDefaults) + ", as kdop gen and taa]")
        ->check(SelectionOptions::choice("mode", "clip or varclip", parse_mode));
    cmd->add_option("--neighborhoods", o->run.neighborhoods,
                    "n9 and/or n5 [default: " + default_neighborhoods_text(kCommandDefaults) + ", as kdop gen and taa]")
        ->check(SelectionOptions::choice("neighborhood", "n9 or n5", parse_neighborhood));
    cmd->add_option("--budget-ops", o->run.budget_ops,
                    "Recommend the least held-out ghosting among the candidates whose clip costs at most this many "
                    "float ops, as kdop gen and kdop bench count them [default: no budget]")
        ->check(whole_number(1, 1000000));
    cmd->add_option("--budget-ms", o->run.budget_ms,
                    "Or among those whose rectification pass takes at most this many ms (median, on the device, as "
                    "kdop taa times it)")
        ->check(positive_number(1e6, " ms"))
        ->excludes("--budget-ops");
    cmd->add_option("--target-ghosting", o->run.target_ghosting,
                    "Recommend instead the cheapest candidate whose held-out ghosting is at most this")
        ->check(positive_number(1))
        ->excludes("--budget-ops")
        ->excludes("--budget-ms");
    cmd->add_option("--timing-rounds", o->run.timing_rounds,
                    "Interleaved dispatches per candidate for ms [default: 15]")
        ->check(whole_number(1, 10000));
    cmd->add_flag("--lavapipe-cost", o->run.lavapipe_cost,
                  "Also count each clip candidate's instructions per pixel on lavapipe beyond the gather, with "
                  "callgrind, as kdop bench does (seconds per candidate; varclip has no such count)");
    cmd->add_option("--warmup", o->run.evaluation.schedule.warmup,
                    "Frames of each sequence before measuring [default: 100]")
        ->check(whole_number(1, 100000));
    add_resolve_options(*cmd, o->run.evaluation.resolve);
    add_own_resolve_options(*cmd, o->own_resolve);
    add_input_space_option(*cmd, o->run.input_space);
    cmd->add_option("--ppd", o->ppd, "FLIP's pixels per degree [default: as kdop taa's, about 67]")
        ->check(finite_number(kMinPixelsPerDegree, kMaxPixelsPerDegree));
    cmd->add_option("--sample", o->run.sample, "Fit to this many sampled neighborhoods (as kdop optimize --sample)")
        ->check(whole_number(1, (1ll << 40)));
    cmd->add_option("--seed", o->run.seed,
                    "Seed of the fit and of the bootstrap of the held-out ghosting's intervals [default: 1]")
        ->check(seed_number());
    cmd->add_option("--threads", o->run.threads, "Threads of the fit [default: one per core]")->check(thread_count());
    cmd->add_option(
        "--device", o->device,
        "Vulkan device: a substring of its name, or gpu for the first GPU [default: $KDOP_DEVICE, else lavapipe]");
    cmd->add_flag(
        "--no-charts", [o](std::int64_t) { o->run.chart = false; }, "Write the tables and report without choice.png");
    cmd->add_option("--out", o->run.out, "Output directory (created if missing)")->required();

    return [o, cmd] {
        o->run.evaluation.ppd = cmd->count("--ppd") ? o->ppd : pixels_per_degree(ViewingConditions{});
        auto ranks = Ranks::world();
        if (!ranks) return report_error(ranks.error().message);
        (*ranks)->quiet_unless_root();
        auto outputs = OutputSet::prepare(o->run.out);
        auto context = outputs ? Context::create({o->device, false}) : std::unexpected(outputs.error());
        // Every rank checks the folder and opens a device: one that cannot must not leave the others
        // waiting in the fit.
        if (auto ok = (*ranks)->agree(context ? Result<void>{} : std::unexpected(context.error())); !ok)
            return report_error(ok.error().message);
        // A folder of sequences or a list file stands for the sequences it names.
        for (auto [option, sequences] : {std::pair{"--fit", &o->run.fit}, std::pair{"--validate", &o->run.validate}}) {
            auto expanded = expand_sequence_arguments(*sequences, option);
            if (!expanded) return report_error(expanded.error().message);
            *sequences = std::move(*expanded);
        }
        if (auto conflict = check(o->run)) return usage_error(conflict_message(*conflict));
        OwnResolveChoice own = own_resolve_choice(*cmd, o->own_resolve);
        if (!own.usage.empty()) return usage_error(own.usage);
        if (!own.input.empty()) return report_error(own.input);
        o->run.evaluation.own_resolve = std::move(own.resolve);
        auto chosen = run_choose(**context, o->run, **ranks, *outputs);
        if (!chosen) return report(chosen.error());
        if (!(*ranks)->is_root()) return 0;
        const Recommendation& r = chosen->recommendation;
        std::cout << (r.chosen ? fmt::format("kdop choose: {}: {}.\n{}\n", chosen->candidates[*r.chosen].key.name(),
                                             r.why, r.noise)
                               : fmt::format("kdop choose: no recommendation: {}\n", r.why))
                  << terminal_text((outputs->dir() / "choice.md").string()) << "\n";
        return 0;
    };
}

} // namespace kdop::cli
