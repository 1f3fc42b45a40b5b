#include "cli/commands.h"

#include "cli/number_option.h"
#include "generator/selection_options.h"
#include "harness/variant_catalog.h"
#include "stress/stress_report.h"
#include "stress/stress_study.h"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>

namespace kdop::cli {

Action add_stress_command(CLI::App& app) {
    struct Options {
        std::string out, device;
        SelectionOptions selection;
        std::uint64_t seed = 1;
        double gamma = 1.0;
        bool validation = false;
    };
    auto o = std::make_shared<Options>();
    CLI::App* stress = app.add_subcommand(
        "stress", "Run variants over extreme inputs (HDR up to FLT_MAX, denormals, flat and gray neighborhoods, rays "
                  "parallel to a slab, NaN and Inf history or neighbors, rgba16f) and check every pixel against the "
                  "double-precision reference; prints a table of variants x cases. Exits 3 if an invariant broke");
    stress->add_option("--out", o->out,
                       "Also write stress.csv, stress.json and report.md to this directory (created if missing)");
    stress->add_option(
        "--device", o->device,
        "Vulkan device: a substring of its name, or gpu for the first GPU [default: $KDOP_DEVICE, else lavapipe]");
    o->selection.add_to(*stress);
    stress->add_option("--seed", o->seed, "Seed of the random colors [default: 1]")->check(seed_number());
    stress->add_option("--gamma", o->gamma, "Variance-clip slab half-width in standard deviations [default: 1]")
        ->check(gamma_number());
    stress->add_flag("--validation", o->validation, "Enable the Khronos validation layer (slower)");

    return [o] {
        if (o->selection.baselines)
            return report_error("--baselines: the gather and copy baselines are not clips; nothing to stress");
        if (!std::isfinite(o->gamma) || o->gamma < 0)
            return report_error(fmt::format("--gamma: must be a finite number >= 0, got {}", o->gamma));
        auto specs = o->selection.select();
        if (!specs) return report_error(specs.error().message);
        auto catalog = VariantCatalog::create(o->selection.sets, o->selection.style());
        if (!catalog) return report_error(catalog.error().message);

        auto study =
            stress_study(*specs, *catalog, {o->out, o->seed, static_cast<float>(o->gamma), {o->device, o->validation}});
        if (!study) return report_error(study.error().message);
        report_validation_messages(study->validation_messages);
        const StressRun& run = study->run;
        std::cout << fmt::format("kdop stress: {} variants x {} cases on {} ({}), seed {}\n\n", run.variants.size(),
                                 run.cases.size(), study->run_info.device, study->run_info.driver, o->seed)
                  << stress_table_text(run);
        // 3, not 1 (failed to run) or 2 (usage): the run worked and found broken invariants.
        return run.failing_cells() ? 3 : 0;
    };
}

} // namespace kdop::cli
