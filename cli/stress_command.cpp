#include "cli/commands.h"

#include "cli/number_option.h"
#include "generator/selection_options.h"
#include "harness/device_runner.h"
#include "harness/output_set.h"
#include "harness/progress.h"
#include "harness/run_metadata.h"
#include "harness/variant_catalog.h"
#include "runtime/context.h"
#include "stress/stress_report.h"
#include "stress/stress_suite.h"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <optional>

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
    stress->add_option("--device", o->device,
                       "Vulkan device: a substring of its name [default: $KDOP_DEVICE, else lavapipe]");
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
        std::optional<OutputSet> outputs;
        if (!o->out.empty()) {
            auto prepared = OutputSet::prepare(o->out);
            if (!prepared) return report_error(prepared.error().message);
            outputs = std::move(*prepared);
        }
        auto specs = o->selection.select();
        if (!specs) return report_error(specs.error().message);
        auto catalog = VariantCatalog::create(o->selection.sets, o->selection.style());
        if (!catalog) return report_error(catalog.error().message);
        auto context = Context::create({o->device, o->validation});
        if (!context) return report_error(context.error().message);

        StressOptions options{{}, o->seed, static_cast<float>(o->gamma)};
        options.variants = keys_of(*specs);
        DeviceRunner runner(**context);
        Progress progress(fmt::format("stress on {},", (*context)->device_name()), stress_steps(options));
        auto run = run_stress(runner, *catalog, options, &progress);
        progress.finish();
        if (!run) return report_error(run.error().message);
        report_validation_messages(**context);

        RunMetadata run_info = describe_run(**context);
        run_info.seed = o->seed;
        if (outputs) {
            outputs->add_table("stress", stress_table(*run), run_info);
            outputs->add("report.md", stress_report_markdown(*run, run_info, static_cast<float>(o->gamma)));
            if (auto ok = outputs->write(); !ok) return report_error(ok.error().message);
        }
        std::cout << fmt::format("kdop stress: {} variants x {} cases on {} ({}), seed {}\n\n", run->variants.size(),
                                 run->cases.size(), run_info.device, run_info.driver, o->seed)
                  << stress_table_text(*run);
        // 3, not 1 (failed to run) or 2 (usage): the run worked and found broken invariants.
        return run->failing_cells() ? 3 : 0;
    };
}

} // namespace kdop::cli
