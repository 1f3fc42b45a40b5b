#include "cli/commands.h"

#include "cli/hdr_flip_option.h"
#include "cli/input_space_option.h"
#include "cli/number_option.h"
#include "core/input_files.h"
#include "core/shown_text.h"
#include "core/write_files.h"
#include "flip/flip.h"
#include "flip/flip_check.h"
#include "flip/flip_run.h"
#include "flip/hdr_flip.h"
#include "generator/command_line.h"
#include "harness/statistics.h"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

namespace kdop::cli {
namespace {

// The flag each output is given with.
const char* flag(FlipOutput output) {
    switch (output) {
    case FlipOutput::out: return "--out";
    case FlipOutput::exposure_map: return "--exposure-map";
    case FlipOutput::csv: return "--csv";
    case FlipOutput::histogram: return "--histogram";
    }
    return "";
}

// A conflict of the options (flip_check.h), named by the flags that gave them.
std::string conflict_message(const FlipConflict& conflict, const FlipRunOptions& o) {
    using Kind = FlipConflict::Kind;
    const std::string& path = output_path(o, conflict.output);
    switch (conflict.kind) {
    case Kind::pixels_per_degree: return "--ppd: " + check_pixels_per_degree(o.ppd).error().message;
    case Kind::no_tests: return "--test: give at least one test image";
    case Kind::maps_of_several_tests:
        return fmt::format("--out and --exposure-map write one test's maps, and {} --test images are given; --csv and "
                           "--histogram take several",
                           o.tests.size());
    case Kind::map_format:
        return fmt::format("{}: {}: the map is written as .exr (its values) or .png (in magma colors)",
                           flag(conflict.output), path);
    case Kind::histogram_format:
        return fmt::format("{}: {}: the histogram is drawn as a .png", flag(conflict.output), path);
    case Kind::same_output:
        return fmt::format("{} and {} both name {}", flag(conflict.earlier), flag(conflict.output), path);
    }
    return "";
}

// The options' conflicts and the files the run would be refused, before any work: exit 2. Every
// output is checked: none a folder, a special file or an input.
std::optional<int> refused(const FlipRunOptions& o) {
    if (auto conflict = check(o)) return usage_error(conflict_message(*conflict, o));
    std::vector<std::filesystem::path> inputs{o.reference};
    inputs.insert(inputs.end(), o.tests.begin(), o.tests.end());
    for (FlipOutput output : kFlipOutputs) {
        const std::string& path = output_path(o, output);
        if (path.empty()) continue;
        if (auto ok = check_output_file(path, flag(output)); !ok) return usage_error(ok.error().message);
        if (auto ok = check_not_an_input(path, flag(output), inputs); !ok) return report(ok.error());
    }
    return std::nullopt;
}

// What the run found: each test's mean and statistics, the timing; then the files, written.
int print(const FlipRunOptions& run, const FlipRunResult& r) {
    report_validation_messages(r.validation_messages);
    const std::string where = !r.device.empty() ? "on " + r.device
                              : r.cpu_by_default
                                  ? "on the CPU (kdop's default device, lavapipe, is a CPU, where kdop's "
                                    "CPU code is faster; --device llvmpipe computes it there)"
                                  : "on the CPU";
    for (const FlipTestResult& t : r.tests) {
        // With several tests, each block says which.
        const std::string which = r.tests.size() > 1 ? terminal_text(t.test) + ": " : "";
        const FlipStatistics& f = t.statistics;
        if (run.hdr)
            std::cout << fmt::format("{}HDR-FLIP mean {} at {:.4g} pixels per degree ({}x{}{}; {} tone mapper, {} "
                                     "exposure{} from {:.4g} to {:.4g}) {}\n",
                                     which, f.mean, run.ppd, r.width, r.height, r.space,
                                     to_string(run.exposure.tone_mapper), t.range.count, t.range.count == 1 ? "" : "s",
                                     t.range.start, t.range.stop, where);
        else
            std::cout << fmt::format("{}LDR-FLIP mean {} at {:.4g} pixels per degree ({}x{}{}) {}\n", which, f.mean,
                                     run.ppd, r.width, r.height, r.space, where);
        std::cout << fmt::format("  weighted median {:.6f}, 1st weighted quartile {:.6f}, 3rd weighted quartile "
                                 "{:.6f} (NVlabs/flip's)\n  median {:.6f}, 1st quartile {:.6f}, 3rd quartile "
                                 "{:.6f}; min {:.6f}, max {:.6f}\n",
                                 f.weighted_median, f.weighted_q1, f.weighted_q3, f.median, f.q1, f.q3, f.min, f.max);
    }
    if (run.timing)
        std::cout << fmt::format("timing: median of {} evaluation{}: {:.4f} s wall, {:.4f} CPU s; set-up {:.3f} s "
                                 "wall, {:.3f} CPU s\n",
                                 run.timing, run.timing == 1 ? "" : "s", median(r.wall_s), median(r.cpu_s),
                                 r.setup_wall_s, r.setup_cpu_s);
    if (auto ok = write_flip_outputs(run, r); !ok) return report_error(ok.error().message);
    for (const std::string& path : {run.out, run.exposure_map, run.csv, run.histogram})
        if (!path.empty()) std::cout << fmt::format("wrote {}\n", terminal_text(path));
    return 0;
}

} // namespace

Action add_flip_command(CLI::App& app) {
    struct Options {
        FlipRunOptions run;
        ViewingConditions viewing;
        bool srgb = false;
    };
    auto o = std::make_shared<Options>();
    CLI::App* flip = app.add_subcommand(
        "flip", "LDR-FLIP (Andersson et al. 2020), or with --hdr HDR-FLIP (Andersson et al. 2021): the difference a "
                "viewer sees flipping between a reference and each test image; prints the mean and the statistics "
                "NVlabs/flip's tool prints, writes the per-pixel map with --out, a table with --csv and the weighted "
                "histogram with --histogram");
    flip->add_option("--reference", o->run.reference,
                     "Reference image (any OpenImageIO format; RGB from 0 to 1 once decoded, see --input-space)")
        ->required();
    flip->add_option("--test", o->run.tests,
                     "Test images, each the same size as the reference and compared with it on one device")
        ->required();
    auto* ppd = flip->add_option("--ppd", o->run.ppd,
                                 fmt::format("Pixels per degree of visual angle, from {} to {} [default: from the "
                                             "viewing conditions, about 67]",
                                             kMinPixelsPerDegree, kMaxPixelsPerDegree))
                    ->check(finite_number(kMinPixelsPerDegree, kMaxPixelsPerDegree));
    flip->add_option("--distance", o->viewing.distance_m, "Viewing distance in meters [default: 0.7]")
        ->check(positive_number(1e6))
        ->excludes(ppd);
    flip->add_option("--display-width", o->viewing.display_width_m, "Display width in meters [default: 0.7]")
        ->check(positive_number(1e6))
        ->excludes(ppd);
    flip->add_option("--display-pixels", o->viewing.display_width_px, "Display width in pixels [default: 3840]")
        ->check(positive_number(1e6))
        ->excludes(ppd);
    auto* space = add_input_space_option(*flip, o->run.input_space);
    flip->add_flag("--srgb", o->srgb, "The same as --input-space srgb: decode every input from sRGB")->excludes(space);
    flip->add_option(
        "--out", o->run.out,
        "Error map to write (one --test): .exr holds the values (gray), .png shows them in the magma color "
        "map");
    flip->add_option("--csv", o->run.csv,
                     "Write every test's mean, weighted median and quartiles, median and "
                     "quartiles, minimum and maximum to this CSV file");
    flip->add_option("--histogram", o->run.histogram,
                     "Draw every test's weighted FLIP histogram (NVlabs/flip's: each bucket's pixels times its error, "
                     "per megapixel) into this .png (gnuplot)");
    auto* hdr = flip->add_flag("--hdr", o->run.hdr,
                               "HDR-FLIP: linear RGB from 0 up, compared at a range of exposures after tone mapping");
    for (CLI::Option* option : add_hdr_flip_options(*flip, o->run.exposure)) option->needs(hdr);
    auto* cpu = flip->add_flag("--cpu", o->run.cpu,
                               "Compute on the CPU with the reference code the device passes are tested against, not "
                               "on the Vulkan device [the default where no device is named: kdop's default device, "
                               "lavapipe, is a CPU, where this code is faster]");
    flip->add_option("--device", o->run.device.device,
                     "Vulkan device to compute on: a substring of its name, or gpu for the first GPU [default: "
                     "$KDOP_DEVICE; with neither, the CPU]")
        ->excludes(cpu);
    flip->add_flag("--validation", o->run.device.validation, "Enable the Khronos validation layer (slower)")
        ->excludes(cpu);
    flip->add_option(
            "--timing", o->run.timing,
            "Evaluate (the first test) N more times after the first, the mean alone, and print the median wall "
            "and CPU seconds (all threads) "
            "per evaluation, and the set-up's")
        ->check(whole_number(1, 1000));
    flip->add_option("--exposure-map", o->run.exposure_map,
                     "HDR-FLIP: write, per pixel, which exposure gave its error (0 the first, 1 the last) to this "
                     ".exr (the values) or .png (in magma colors; the reference tool draws it in viridis)")
        ->needs(hdr);

    return [o, ppd] {
        const bool viewing = !*ppd;
        FlipRunOptions& run = o->run;
        if (viewing) run.ppd = pixels_per_degree(o->viewing);
        if (o->srgb) run.input_space = InputSpace::srgb;
        if (auto ok = check_pixels_per_degree(run.ppd); !ok)
            return usage_error(viewing ? fmt::format("--distance {} --display-width {} --display-pixels {}: {}",
                                                     o->viewing.distance_m, o->viewing.display_width_m,
                                                     o->viewing.display_width_px, ok.error().message)
                                       : fmt::format("--ppd: {}", ok.error().message));
        if (auto status = refused(run)) return *status;
        auto result = run_flip(run);
        if (!result) return report(result.error());
        return print(run, *result);
    };
}

} // namespace kdop::cli
