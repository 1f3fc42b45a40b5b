#include "cli/commands.h"

#include "accuracy/accuracy_charts.h"
#include "accuracy/accuracy_report.h"
#include "accuracy/accuracy_run.h"
#include "cli/input_space_option.h"
#include "cli/number_option.h"
#include "core/memory_budget.h"
#include "core/shown_text.h"
#include "generator/selection_options.h"
#include "harness/device_runner.h"
#include "harness/gnuplot.h"
#include "harness/output_set.h"
#include "harness/progress.h"
#include "harness/run_metadata.h"
#include "harness/scratch_directory.h"
#include "harness/variant_catalog.h"
#include "runtime/context.h"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>

namespace kdop::cli {

Action add_accuracy_command(CLI::App& app) {
    struct Options {
        std::string out, current, history, cost, device;
        std::vector<std::string> images;
        SelectionOptions selection;
        std::uint32_t size = 128;
        std::uint64_t seed = 1;
        std::size_t volume_samples = 256;
        double gamma = 1.0;
        bool validation = false, no_charts = false;
        InputSpace input_space = InputSpace::from_file;
    };
    auto o = std::make_shared<Options>();
    CLI::App* accuracy = app.add_subcommand(
        "accuracy",
        "Measure how close each variant's clip comes to the ideal clip at the convex hull of the neighborhood "
        "(exact LP on the CPU), on given images or on the built-in texture families and ghosting histories; "
        "writes accuracy.csv, trade.csv (each also as JSON), report.md and a Pareto chart per family");
    accuracy->add_option("--out", o->out, "Output directory (created if missing)")->required();
    auto* current = accuracy->add_option("--current", o->current, "Current frame (needs --history)");
    auto* history = accuracy->add_option("--history", o->history, "History of the same size as --current");
    add_input_space_option(*accuracy, o->input_space);
    current->needs(history);
    history->needs(current);
    accuracy
        ->add_option("--images", o->images,
                     "Current frames, each measured against the built-in ghosting histories (shifted, moved-object, "
                     "other-texture: the image rotated by 180 degrees)")
        ->excludes(current)
        ->excludes(history);
    accuracy
        ->add_option("--size", o->size, "Without --current or --images: the built-in content's size NxN [default: 128]")
        ->check(whole_number(8, 4096));
    accuracy->add_option("--cost", o->cost,
                         "A `kdop bench` cost.csv: adds lavapipe's marginal cost to the trade table and charts");
    o->selection.add_to(*accuracy);
    accuracy->add_option("--gamma", o->gamma, "Variance-clip slab half-width in standard deviations [default: 1]")
        ->check(gamma_number());
    accuracy->add_option("--seed", o->seed, "Seed of the built-in content and the volume sample [default: 1]")
        ->check(seed_number());
    accuracy
        ->add_option("--volume-samples", o->volume_samples,
                     "Pixels per pair and neighborhood for the k-DOP/hull volume ratio; 0 skips it [default: 256]")
        ->check(whole_number(0, 1 << 20));
    accuracy->add_option("--device", o->device,
                         "Vulkan device: a substring of its name [default: $KDOP_DEVICE, else lavapipe]");
    accuracy->add_flag("--validation", o->validation, "Enable the Khronos validation layer (slower)");
    accuracy->add_flag("--no-charts", o->no_charts, "Write the tables and report without the Pareto charts");

    return [o, accuracy] {
        if (o->selection.baselines)
            return report_error("--baselines: the gather and copy baselines are not clips; they have no accuracy");
        if (!std::isfinite(o->gamma) || o->gamma < 0)
            return report_error(fmt::format("--gamma: must be a finite number >= 0, got {}", o->gamma));
        const bool builtin = o->current.empty() && o->images.empty();
        if (!builtin && accuracy->count("--size"))
            return report_error(
                "--size: only for the built-in content; --current and --images are measured at their own size");
        auto outputs = OutputSet::prepare(o->out);
        if (!outputs) return report_error(outputs.error().message);
        auto specs = o->selection.select();
        if (!specs) return report_error(specs.error().message);
        warn_fitted_space(*specs, ColorMap{}, "kdop accuracy (on linear values)");
        auto catalog = VariantCatalog::create(o->selection.sets, o->selection.style());
        if (!catalog) return report_error(catalog.error().message);
        std::map<VariantKey, LavapipeCost> costs;
        if (!o->cost.empty()) {
            auto read = read_bench_costs(o->cost);
            if (!read) return report_error(read.error().message);
            costs = std::move(*read);
        }

        std::vector<AccuracyPair> pairs;
        // The built-in content is made whole before the run: 27 pairs of images, and the textures
        // they are made from.
        if (auto ok = check_memory(fmt::format("--size {}", o->size), 64 * image_bytes(o->size, o->size));
            builtin && !ok)
            return report_error(ok.error().message);
        if (builtin) {
            pairs = builtin_pairs(o->size, o->size, o->seed);
        } else if (!o->images.empty()) {
            auto read = image_pairs(o->images, o->input_space);
            if (!read) return report_error(read.error().message);
            pairs = std::move(*read);
        } else {
            auto read = given_pair(o->current, o->history, o->input_space);
            if (!read) return report_error(read.error().message);
            pairs.push_back(std::move(*read));
        }

        const bool charts = charts_available(!o->no_charts);
        ScratchDirectory scratch("kdop-accuracy");
        if (scratch.path.empty()) return report_error("cannot create a scratch directory in the temporary directory");
        auto context = Context::create({o->device, o->validation});
        if (!context) return report_error(context.error().message);

        AccuracyOptions options{{}, static_cast<float>(o->gamma), o->volume_samples, o->seed};
        options.variants = keys_of(*specs);
        DeviceRunner runner(**context);
        Progress progress(fmt::format("accuracy of {} variants on {},", specs->size(), (*context)->device_name()),
                          accuracy_steps(options, pairs.size()));
        auto run = run_accuracy(runner, *catalog, options, pairs, &progress);
        progress.finish();
        if (!run) return report_error(run.error().message);
        report_validation_messages(**context);

        RunMetadata run_info = describe_run(**context);
        run_info.seed = o->seed;
        const std::vector<TradeRow> trade = trade_rows(*run, costs);
        // A chart that fails costs the charts, not the run: the data and report are still written.
        auto drawn = charts ? accuracy_charts(trade, scratch.path, outputs->dir())
                            : Result<std::vector<OutputFile>>(std::vector<OutputFile>{});
        if (!drawn) warn_no_charts(drawn.error().message);
        const bool drew = charts && drawn;
        if (drew) outputs->add(std::move(*drawn));
        outputs->add_table("accuracy", accuracy_table(*run), run_info);
        outputs->add_table("trade", trade_table(trade), run_info);
        outputs->add("report.md",
                     accuracy_report_markdown(*run, trade, run_info,
                                              {o->cost, static_cast<float>(o->gamma), o->volume_samples, drew}));
        if (auto ok = outputs->write(); !ok) return report_error(ok.error().message);
        std::cout << fmt::format("kdop accuracy: {} variants x {} pairs on {} ({}): {}\n", specs->size(), pairs.size(),
                                 run_info.device, run_info.driver,
                                 terminal_text((outputs->dir() / "report.md").string()));
        return 0;
    };
}

} // namespace kdop::cli
