// kdop optimize: fit an axis set to a scene's images (every neighborhood) or, scene-independent,
// around the unit sphere, and write it as an axis-set file every command reads.
#include "cli/commands.h"

#include "cli/color_map_option.h"
#include "cli/input_space_option.h"
#include "cli/number_option.h"
#include "cli/resolve_option.h"
#include "core/shown_text.h"
#include "core/write_files.h"
#include "generator/command_line.h"
#include "optimize/fit_check.h"
#include "optimize/optimize.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>

#include <sys/resource.h>

namespace kdop::cli {
namespace {

// The command line's options: the run's, and the two it takes as words.
struct Options {
    OptimizeOptions run;
    std::string neighborhood = "n9", objective = "volume";
};

// This process's peak resident memory, in MB.
double peak_memory_mb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0; // kilobytes on Linux
}

// A conflict of the options (fit_check.h), named by the flags that gave them.
std::string conflict_message(FitConflict conflict, const OptimizeOptions& o, int ranks) {
    const std::string name_option = o.name.empty() ? "--out" : "--name";
    switch (conflict) {
    case FitConflict::distance_without_samples:
        return "--objective distance: the distance is taken on --accuracy-samples pixels; give more than 0";
    case FitConflict::cost_without_table:
        return "--lavapipe-cost: counts the rows of --target's, --target-ghosting's or --max-nonzero's table; give "
               "one of them";
    case FitConflict::rgb_fills_axes:
        return fmt::format("--force-rgb fixes 3 axes; --axes {} leaves none to fit", o.axes);
    case FitConflict::nonzero_below_axes:
        return fmt::format("--max-nonzero {}: each of the {} axes keeps at least one component", *o.max_nonzero,
                           o.axes);
    case FitConflict::not_a_set_name:
        return fmt::format("{}: '{}' is not a set name (lowercase letters and digits, single '-' between words); "
                           "give one with --name",
                           name_option, set_name(o));
    case FitConflict::builtin_set_name:
        return fmt::format("{}: '{}' is the name of a built-in set, which every command would take instead of this "
                           "file; give another with --name",
                           name_option, set_name(o));
    case FitConflict::sphere_over_ranks:
        return fmt::format("mpirun -np {}: --sphere has no frames to share over ranks (it takes well under a "
                           "second); run it without mpirun",
                           ranks);
    }
    return "";
}

// The options' conflicts and the --out file the run would be refused, before any work: exit 2.
std::optional<int> refused(const OptimizeOptions& o, int ranks) {
    if (auto conflict = check(o)) return usage_error(conflict_message(*conflict, o, ranks));
    if (std::error_code ec; std::filesystem::is_directory(o.out, ec))
        return usage_error(fmt::format("--out {}: is a directory; name the axis-set file to write", o.out));
    if (auto ok = check_output_file(o.out, "--out"); !ok) return usage_error(ok.error().message);
    if (auto conflict = check_ranks(o, ranks)) return usage_error(conflict_message(*conflict, o, ranks));
    return std::nullopt;
}

// What the run found, as the command prints it after the file is written.
int print(const OptimizeOptions& o, const OptimizeResult& r, const Ranks& ranks) {
    std::cout << fmt::format("{}: {} axes, {} = {:.6g}\n", terminal_text(o.out), r.fit.axes.size(), r.fitted_objective,
                             r.fitted_score);
    if (!r.sample_line.empty()) std::cout << r.sample_line << "\n";
    if (!r.refined_line.empty()) std::cout << r.refined_line << "\n";
    if (!r.distance_measure.empty()) std::cout << fmt::format("{}: {:.6g}\n", r.distance_measure, r.sets[0].distance);
    const auto compared = compared_set_columns(r.sets[0], !r.distance_measure.empty());
    std::cout << "  " << printed_header(compared) << "\n";
    for (const ComparedSet& set : r.sets) std::cout << "  " << printed_row(compared, set) << "\n";
    if (!r.closer_warning.empty()) std::cout << fmt::format("warning: {}\n", r.closer_warning);
    // Volumes in the objective per second; a neighborhood repeated in the images is computed once.
    std::cout << fmt::format(
        "{:.1f} s, {} k-DOP volumes, {:.3g} per second{}{}{}\n", r.fit.seconds, r.fit.volumes,
        r.fit.volumes / std::max(r.fit.seconds, 1e-9),
        r.fit.computed < r.fit.volumes ? fmt::format(" ({} computed, repeated neighborhoods once)", r.fit.computed)
                                       : "",
        r.fit.failed ? fmt::format(", {} polytopes left out (could not be built)", r.fit.failed) : "",
        r.fit.stopped_early ? "; stopped early by --time-limit" : "");
    // What the frames cost in memory: bounded by what is held, whatever the frame count.
    if (r.own_frames)
        std::cout << fmt::format("peak memory {:.0f} MB; {} of {} frames held between passes, the rest read again on "
                                 "each{}\n",
                                 peak_memory_mb(), r.held_frames, r.own_frames,
                                 ranks.size() > 1 ? fmt::format(" (on rank 0 of {}, which reads {} of the {} frames)",
                                                                ranks.size(), r.own_frames, r.frames)
                                                  : "");
    return 0;
}

} // namespace

Action add_optimize_command(CLI::App& app) {
    auto o = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand(
        "optimize", "Fit an axis set to a scene's images and frame sequences (every neighborhood) or around the unit "
                    "sphere, minimizing the k-DOP volume, and write it as an axis-set file; under mpirun, over ranks");
    auto* images =
        cmd->add_option(
               "--images", o->run.input.images,
               "Images to fit to, any format OpenImageIO reads (EXR included), decoded to linear RGB (--input-space)")
            ->check(CLI::ExistingFile);
    auto* sequences = cmd->add_option("--sequence", o->run.input.sequences,
                                      "Frame sequences to fit to (folders with sequence.json, docs/taa.md, "
                                      "\"Frame sequences\"): their frames' colors, with --images or alone")
                          ->check(CLI::ExistingDirectory);
    cmd->add_option("--frame-step", o->run.input.frame_step,
                    "Of each sequence, every Nth frame from the first [default: 1, every frame]")
        ->check(whole_number(1, (1ll << 30)))
        ->needs(sequences);
    auto* sphere =
        cmd->add_flag("--sphere", o->run.sphere, "Fit around the unit sphere instead: a scene-independent set");
    images->excludes(sphere);
    sequences->excludes(sphere);
    cmd->add_option("--memory", o->run.memory,
                    "Hold the frames' neighborhoods between the search's passes up to this many MB (216 bytes a "
                    "pixel at most); the frames beyond are read and gathered again on each pass [default: half the "
                    "available memory; with --sample, none: the search sees the sample alone, and the frames are "
                    "read again for the scores on all of them]")
        ->check(positive_number(1e9, " MB"))
        ->excludes(sphere);
    add_input_space_option(*cmd, o->run.input.input_space)->excludes(sphere);
    add_color_map_option(*cmd, o->run.input.color_map,
                         "The space to fit in, that of the resolve the set is for (kdop taa --color-map): linear, "
                         "gamma:G (G from 0.01 to 100) or log; the file records it as color_map: [default: linear]")
        ->excludes(sphere);
    cmd->add_option("--axes", o->run.axes, "Axes to fit (k = 2 x axes); with --target, the most to try")
        ->required()
        ->check(whole_number(3, 32));
    cmd->add_flag("--force-rgb", o->run.force_rgb, "Keep R, G and B as the first three axes");
    cmd->add_option("--neighborhood", o->neighborhood, "n9 (3x3) or n5 (plus) [default: n9]")
        ->check(CLI::IsMember({"n9", "n5"}))
        ->excludes(sphere);
    cmd->add_option("--seed", o->run.seed, "Seed of the random starts [default: 1]")->check(seed_number());
    cmd->add_option("--starts", o->run.starts, "Starts of the search [default: 64 around the sphere, 4 on images]")
        ->check(whole_number(1, 100000));
    cmd->add_option("--iterations", o->run.iterations, "Steps per start [default: 400 around the sphere, 60 on images]")
        ->check(whole_number(1, 100000));
    cmd->add_option("--threads", o->run.threads, "Threads [default: one per core]; the result does not depend on it")
        ->check(thread_count());
    // Up to a year: a steady_clock deadline much further out would overflow.
    cmd->add_option("--time-limit", o->run.time_limit, "Stop after this many seconds with the best set so far")
        ->check(positive_number(365.0 * 24 * 3600, " seconds (a year)"));
    cmd->add_option("--target", o->run.target,
                    "Fit 3, 4, ... up to --axes axes and keep the first whose score reaches this (a mean volume: "
                    "compare the built-in sets' scores a plain run prints); prints the table of axes, score and cost")
        ->check(positive_number(1e30));
    auto* target_ghosting =
        cmd->add_option("--target-ghosting", o->run.target_ghosting,
                        "Fit 3, 4, ... up to --axes axes and keep the first whose ghosting on every --sequence, "
                        "measured as `kdop taa --sequence` measures it (the resolve in --color-map, with the "
                        "resolve options below, after --warmup frames), is at most this; prints the table of axes, "
                        "volume, ghosting, shimmer and cost")
            ->check(positive_number(1))
            ->needs(sequences)
            ->excludes("--target");
    auto* resolve_options = cmd->add_option_group("Resolve options", "The resolve --target-ghosting measures with");
    add_resolve_options(*resolve_options, o->run.resolve, false);
    for (CLI::Option* option : resolve_options->get_options()) option->needs(target_ghosting);
    cmd->add_option("--warmup", o->run.warmup, "With --target-ghosting: frames before measuring [default: 100]")
        ->check(whole_number(1, 100000))
        ->needs(target_ghosting);
    cmd->add_option("--max-nonzero", o->run.max_nonzero,
                    "Then pin the smallest components at 0, refitting after each, until at most this many are "
                    "nonzero over all axes (a zero costs the clip nothing); prints the curve of score and cost")
        ->check(whole_number(1, 96))
        ->excludes("--target")
        ->excludes(target_ghosting);
    cmd->add_flag("--lavapipe-cost", o->run.lavapipe_cost,
                  "With --target or --max-nonzero: also count each row's clip on lavapipe with callgrind, in "
                  "instructions per pixel beyond the gather, as `kdop bench` does (seconds per row)");
    cmd->add_option(
           "--accuracy-samples", o->run.accuracy_samples,
           "With --images or --sequence: also report each set's mean distance to the ideal clip (as `kdop accuracy` "
           "measures it, in the CPU reference) on this many seeded pixels of each image under each of its "
           "3 ghosting histories (of each sequence as many, spread over its frames); 0 skips it [default: 8192]")
        ->check(whole_number(0, 1 << 24))
        ->excludes(sphere);
    cmd->add_option("--sample", o->run.sample,
                    "Fit to this many neighborhoods, seeded (--seed) and stratified by luminance within each frame, "
                    "then score the set on all of them too (with --target, the sample's score is compared)")
        ->check(whole_number(1, (1ll << 40)))
        ->excludes(sphere);
    cmd->add_option("--objective", o->objective,
                    "volume: the mean k-DOP volume over every neighborhood, or distance: the mean distance to the "
                    "ideal clip over the --accuracy-samples pixels, descended on (the clip's exact subgradient) from "
                    "the volume fit and from each built-in set of as many axes [default: volume]")
        ->check(CLI::IsMember({"volume", "distance"}))
        ->excludes(sphere)
        ->excludes("--target")
        ->excludes("--target-ghosting")
        ->excludes("--max-nonzero")
        ->excludes("--sample");
    cmd->add_option("--out", o->run.out, "Axis-set file to write")->required();
    cmd->add_option("--name", o->run.name, "The set's name [default: the --out file's stem]");
    return [o, images, sequences, sphere] {
        if (!*images && !*sequences && !*sphere)
            return usage_error("optimize: give --images FILE... or --sequence DIR... to fit to, or --sphere");
        auto ranks = Ranks::world();
        if (!ranks) return report_error(ranks.error().message);
        (*ranks)->quiet_unless_root();
        OptimizeOptions options = o->run;
        options.neighborhood = *parse_neighborhood(o->neighborhood); // checked by CLI11
        options.objective =
            o->objective == "distance" ? OptimizeOptions::Objective::distance : OptimizeOptions::Objective::volume;
        if (auto status = refused(options, (*ranks)->size())) return *status;
        auto result = optimize(options, **ranks, [](const std::string& row) { std::cout << row << "\n"; });
        if (!result) return report(result.error());
        return (*ranks)->is_root() ? print(options, *result, **ranks) : 0;
    };
}

} // namespace kdop::cli
