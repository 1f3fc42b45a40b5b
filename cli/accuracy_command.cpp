#include "cli/commands.h"

#include "accuracy/accuracy_study.h"
#include "cli/input_space_option.h"
#include "cli/number_option.h"
#include "core/shown_text.h"
#include "generator/selection_options.h"
#include "harness/variant_catalog.h"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>

namespace kdop::cli {

Action add_accuracy_command(CLI::App& app) {
    struct Options {
        AccuracyStudyOptions study;
        SelectionOptions selection;
        double gamma = 1.0;
        bool no_charts = false;
    };
    auto o = std::make_shared<Options>();
    CLI::App* accuracy = app.add_subcommand(
        "accuracy",
        "Measure how close each variant's clip comes to the ideal clip at the convex hull of the neighborhood "
        "(exact LP on the CPU), on given images or on the built-in texture families and ghosting histories; "
        "writes accuracy.csv, trade.csv (each also as JSON), report.md and a Pareto chart per family");
    accuracy->add_option("--out", o->study.out, "Output directory (created if missing)")->required();
    auto* current = accuracy->add_option("--current", o->study.content.current, "Current frame (needs --history)");
    auto* history =
        accuracy->add_option("--history", o->study.content.history, "History of the same size as --current");
    add_input_space_option(*accuracy, o->study.content.input_space);
    current->needs(history);
    history->needs(current);
    accuracy
        ->add_option("--images", o->study.content.images,
                     "Current frames, each measured against the built-in ghosting histories (shifted, moved-object, "
                     "other-texture: the image rotated by 180 degrees)")
        ->excludes(current)
        ->excludes(history);
    accuracy
        ->add_option("--size", o->study.content.size,
                     "Without --current or --images: the built-in content's size NxN [default: 128]")
        ->check(whole_number(8, 4096));
    accuracy->add_option("--cost", o->study.cost,
                         "A `kdop bench` cost.csv: adds lavapipe's marginal cost to the trade table and charts");
    o->selection.add_to(*accuracy);
    accuracy->add_option("--gamma", o->gamma, "Variance-clip slab half-width in standard deviations [default: 1]")
        ->check(gamma_number());
    accuracy
        ->add_option("--seed", o->study.content.seed, "Seed of the built-in content and the volume sample [default: 1]")
        ->check(seed_number());
    accuracy
        ->add_option("--volume-samples", o->study.volume_samples,
                     "Pixels per pair and neighborhood for the k-DOP/hull volume ratio; 0 skips it [default: 256]")
        ->check(whole_number(0, 1 << 20));
    accuracy->add_option(
        "--device", o->study.device.device,
        "Vulkan device: a substring of its name, or gpu for the first GPU [default: $KDOP_DEVICE, else lavapipe]");
    accuracy->add_flag("--validation", o->study.device.validation, "Enable the Khronos validation layer (slower)");
    accuracy->add_flag("--no-charts", o->no_charts, "Write the tables and report without the Pareto charts");

    return [o, accuracy] {
        if (o->selection.baselines)
            return report_error("--baselines: the gather and copy baselines are not clips; they have no accuracy");
        if (!std::isfinite(o->gamma) || o->gamma < 0)
            return report_error(fmt::format("--gamma: must be a finite number >= 0, got {}", o->gamma));
        if ((!o->study.content.current.empty() || !o->study.content.images.empty()) && accuracy->count("--size"))
            return report_error(
                "--size: only for the built-in content; --current and --images are measured at their own size");
        auto specs = o->selection.select();
        if (!specs) return report_error(specs.error().message);
        warn_fitted_space(*specs, ColorMap{}, "kdop accuracy (on linear values)");
        auto catalog = VariantCatalog::create(o->selection.sets, o->selection.style());
        if (!catalog) return report_error(catalog.error().message);

        o->study.gamma = static_cast<float>(o->gamma);
        o->study.charts = !o->no_charts;
        auto study = accuracy_study(*specs, *catalog, o->study);
        if (!study) return report_error(study.error().message);
        report_validation_messages(study->validation_messages);
        std::cout << fmt::format("kdop accuracy: {} variants x {} pairs on {} ({}): {}\n", study->variants,
                                 study->pairs, study->run.device, study->run.driver,
                                 terminal_text(study->report.string()));
        return 0;
    };
}

} // namespace kdop::cli
