#include "cli/commands.h"

#include "bench/cost_study.h"
#include "cli/number_option.h"
#include "cli/size_option.h"
#include "core/parallel_for.h"
#include "core/shown_text.h"
#include "generator/selection_options.h"
#include "harness/variant_catalog.h"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>

namespace kdop::cli {

Action add_bench_command(CLI::App& app) {
    struct Options {
        bench::CostStudyOptions study;
        std::string size = "1920x1080", numerics = "hardened";
        std::vector<std::string> variants, sets,
            sweep_sizes{"256x256", "512x512", "1024x1024", "1920x1080", "2560x1440", "3840x2160"};
        bool no_sweep = false, no_callgrind = false, no_charts = false;
    };
    auto o = std::make_shared<Options>();
    o->study.bench.jobs = core_count();
    CLI::App* bench = app.add_subcommand(
        "bench", "Measure what each variant costs: static float-op counts against the supplement's listing and the "
                 "analytic lower bound, "
                 "interleaved timings, a size sweep and callgrind instruction counts; writes cost.csv, cost.json, "
                 "report.md and charts");
    bench->add_option("--out", o->study.out, "Output directory (created if missing)")->required();
    bench
        ->add_option("--sets", o->sets,
                     "Axis sets to measure: built-in names or .axes files [default: every built-in set]; with "
                     "--variants, the files whose sets they name")
        ->check(SelectionOptions::axis_set_name());
    bench->add_option("--variants", o->variants,
                      "Clip variants to measure by name (e.g. dop32-clip-n9, my-set-varclip-n5); their loop forms and "
                      "paper twins come along [default: every clip of --sets]");
    bench->add_option("--numerics", o->numerics, "Numerics of the default selection: hardened or paper")
        ->check(CLI::IsMember({"hardened", "paper"}));
    bench->add_option("--size", o->size, "Timing size WIDTHxHEIGHT [default: 1920x1080]");
    bench
        ->add_option("--repeat", o->study.bench.rounds,
                     "Dispatches per kernel at the timing size (interleaved rounds) [default: 15]")
        ->check(whole_number(1, 10000));
    auto* sweep_sizes =
        bench->add_option("--sweep-sizes", o->sweep_sizes, "Sizes of the size sweep [default: 256x256 ... 3840x2160]");
    auto* sweep_repeat =
        bench->add_option("--sweep-repeat", o->study.bench.sweep_rounds, "Rounds per sweep size [default: 5]")
            ->check(whole_number(1, 10000));
    bench->add_flag("--no-sweep", o->no_sweep, "Skip the size sweep")->excludes(sweep_sizes)->excludes(sweep_repeat);
    auto* callgrind_size = bench
                               ->add_option("--callgrind-size", o->study.bench.callgrind_size,
                                            "Callgrind dispatch size N (NxN pixels) [default: 256]")
                               ->check(whole_number(8, 4096));
    auto* jobs = bench->add_option("--jobs", o->study.bench.jobs, "Callgrind runs at a time [default: one per core]")
                     ->check(whole_number(1, 256));
    bench->add_flag("--no-callgrind", o->no_callgrind, "Skip the callgrind instruction counts")
        ->excludes(callgrind_size)
        ->excludes(jobs);
    bench->add_flag("--no-charts", o->no_charts, "Write the table and report without charts");
    bench->add_option(
        "--device", o->study.bench.device,
        "Vulkan device: a substring of its name, or gpu for the first GPU [default: $KDOP_DEVICE, else lavapipe]");

    return [o, bench] {
        auto catalog = VariantCatalog::create(o->sets);
        if (!catalog) return report_error(catalog.error().message);
        if (!o->variants.empty() && bench->count("--numerics"))
            return report_error(
                "--numerics: only for the default selection; name paper variants in --variants instead");
        bench::CostStudyOptions& options = o->study;
        options.charts = !o->no_charts;
        auto variants = bench::bench_variants(*catalog, o->variants, *parse_numerics(o->numerics));
        if (!variants) return report_error(variants.error().message);
        options.bench.variants = std::move(*variants);
        auto size = size_option("--size", o->size);
        if (!size) return usage_error(size.error().message);
        options.bench.timing_size = *size;
        if (!o->no_sweep)
            for (const std::string& text : o->sweep_sizes) {
                auto s = size_option("--sweep-sizes", text);
                if (!s) return usage_error(s.error().message);
                options.bench.sweep_sizes.push_back(*s);
            }
        options.bench.callgrind = !o->no_callgrind;

        auto study =
            bench::cost_study(*catalog, options, std::filesystem::read_symlink("/proc/self/exe").parent_path());
        if (!study) return report_error(study.error().message);
        std::cout << fmt::format("wrote {} files to {} ({} variants on {})\n", study->files,
                                 terminal_text(o->study.out.string()), study->variants, study->run.device);
        return 0;
    };
}

} // namespace kdop::cli
