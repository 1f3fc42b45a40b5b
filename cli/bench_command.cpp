#include "cli/commands.h"

#include "bench/cost_bench.h"
#include "bench/cost_report.h"
#include "cli/number_option.h"
#include "cli/size_option.h"
#include "core/memory_budget.h"
#include "core/parallel_for.h"
#include "core/shown_text.h"
#include "generator/selection_options.h"
#include "harness/gnuplot.h"
#include "harness/output_set.h"
#include "harness/run_metadata.h"
#include "harness/scratch_directory.h"
#include "harness/variant_catalog.h"

#include <fmt/format.h>

#include <charconv>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

namespace kdop::cli {

Action add_bench_command(CLI::App& app) {
    struct Options {
        std::string out, size = "1920x1080", device, numerics = "hardened";
        std::vector<std::string> variants, sets,
            sweep_sizes{"256x256", "512x512", "1024x1024", "1920x1080", "2560x1440", "3840x2160"};
        unsigned repeat = 15, sweep_repeat = 5, callgrind_size = 256, jobs = core_count();
        bool no_sweep = false, no_callgrind = false, no_charts = false;
    };
    auto o = std::make_shared<Options>();
    CLI::App* bench = app.add_subcommand(
        "bench", "Measure what each variant costs: static float-op counts against the supplement's listing and the "
                 "analytic lower bound, "
                 "interleaved timings, a size sweep and callgrind instruction counts; writes cost.csv, cost.json, "
                 "report.md and charts");
    bench->add_option("--out", o->out, "Output directory (created if missing)")->required();
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
        ->add_option("--repeat", o->repeat,
                     "Dispatches per kernel at the timing size (interleaved rounds) [default: 15]")
        ->check(whole_number(1, 10000));
    auto* sweep_sizes =
        bench->add_option("--sweep-sizes", o->sweep_sizes, "Sizes of the size sweep [default: 256x256 ... 3840x2160]");
    auto* sweep_repeat = bench->add_option("--sweep-repeat", o->sweep_repeat, "Rounds per sweep size [default: 5]")
                             ->check(whole_number(1, 10000));
    bench->add_flag("--no-sweep", o->no_sweep, "Skip the size sweep")->excludes(sweep_sizes)->excludes(sweep_repeat);
    auto* callgrind_size =
        bench
            ->add_option("--callgrind-size", o->callgrind_size, "Callgrind dispatch size N (NxN pixels) [default: 256]")
            ->check(whole_number(8, 4096));
    auto* jobs = bench->add_option("--jobs", o->jobs, "Callgrind runs at a time [default: one per core]")
                     ->check(whole_number(1, 256));
    bench->add_flag("--no-callgrind", o->no_callgrind, "Skip the callgrind instruction counts")
        ->excludes(callgrind_size)
        ->excludes(jobs);
    bench->add_flag("--no-charts", o->no_charts, "Write the table and report without charts");
    bench->add_option("--device", o->device,
                      "Vulkan device: a substring of its name [default: $KDOP_DEVICE, else lavapipe]");

    return [o, bench] {
        auto outputs = OutputSet::prepare(o->out);
        if (!outputs) return report_error(outputs.error().message);
        auto catalog = VariantCatalog::create(o->sets);
        if (!catalog) return report_error(catalog.error().message);
        if (!o->variants.empty() && bench->count("--numerics"))
            return report_error(
                "--numerics: only for the default selection; name paper variants in --variants instead");

        bench::BenchOptions options;
        if (o->variants.empty()) options.variants = catalog->clip_keys(*parse_numerics(o->numerics));
        for (const std::string& name : o->variants) {
            auto key = parse_variant_key(name, "--variants");
            if (!key) return report_error(key.error().message);
            if (!key->is_clip() || key->form != Form::unrolled)
                return report_error(
                    fmt::format("--variants: '{}' is not a clip in its unrolled form; loop forms and the "
                                "gather and copy baselines are measured beside every clip",
                                name));
            if (std::ranges::find(options.variants, *key) != options.variants.end())
                return report_error(fmt::format("--variants: '{}' is given twice", name));
            if (auto set = catalog->set(key->set, "--variants"); !set) return report_error(set.error().message);
            options.variants.push_back(*key);
        }
        auto size = size_option("--size", o->size);
        if (!size) return usage_error(size.error().message);
        options.timing_size = *size;
        options.rounds = o->repeat;
        if (!o->no_sweep)
            for (const std::string& text : o->sweep_sizes) {
                auto s = size_option("--sweep-sizes", text);
                if (!s) return usage_error(s.error().message);
                options.sweep_sizes.push_back(*s);
            }
        options.sweep_rounds = o->sweep_repeat;
        options.callgrind = !o->no_callgrind;
        options.callgrind_size = o->callgrind_size;
        options.jobs = o->jobs;
        options.device = o->device;
        options.probe = std::filesystem::read_symlink("/proc/self/exe").parent_path() / "kdop-dispatch-probe";
        if (options.callgrind && !std::filesystem::exists(options.probe))
            return report_error(
                fmt::format("{} is missing (it is built with kdop); or pass --no-callgrind", options.probe.string()));
        const bool charts = charts_available(!o->no_charts);
        ScratchDirectory scratch("kdop-bench");
        if (scratch.path.empty()) return report_error("cannot create a scratch directory in the temporary directory");
        options.scratch = scratch.path;
        auto context = Context::create({o->device, false});
        if (!context) return report_error(context.error().message);

        auto result = bench::run_cost_bench(**context, *catalog, options);
        if (!result) return report_error(result.error().message);

        const RunMetadata run_info = describe_run(**context);
        bench::ReportSettings settings{options, {}};
        if (charts) {
            // A chart that fails costs the chart, not the run: the data and report are still written.
            auto drawn = bench::cost_charts(*result, run_info.device, scratch.path, outputs->dir());
            if (drawn) {
                settings.charts = bench::cost_chart_names(*result);
                outputs->add(std::move(*drawn));
            } else {
                warn_no_charts(drawn.error().message);
            }
        }
        outputs->add_table("cost", bench::cost_table(result->rows), run_info);
        outputs->add("report.md", bench::cost_report_markdown(*result, run_info, settings));
        if (auto ok = outputs->write(); !ok) return report_error(ok.error().message);
        std::cout << fmt::format("wrote {} files to {} ({} variants on {})\n", outputs->size(), terminal_text(o->out),
                                 options.variants.size(), run_info.device);
        return 0;
    };
}

} // namespace kdop::cli
