#include "commands.h"

#include "context.h"
#include "write_files.h"
#include "progress.h"
#include "run_info.h"
#include "selection_options.h"
#include "stress_report.h"
#include "stress_suite.h"

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
                  "double-precision reference; prints a table of variants x cases. Exits 2 if an invariant broke");
    stress->add_option("--out", o->out, "Also write stress.csv and report.md to this directory (created if missing)");
    stress->add_option("--device", o->device, "Vulkan device: a substring of its name [default: $KDOP_DEVICE, else lavapipe]");
    o->selection.add_to(*stress);
    stress->add_option("--seed", o->seed, "Seed of the random colors [default: 1]");
    stress->add_option("--gamma", o->gamma, "Variance-clip slab half-width in standard deviations [default: 1]");
    stress->add_flag("--validation", o->validation, "Enable the Khronos validation layer (slower)");

    return [o] {
        if (o->selection.baselines) return report_error("--baselines: the gather and copy baselines are not clips; nothing to stress");
        if (!std::isfinite(o->gamma) || o->gamma < 0)
            return report_error(fmt::format("--gamma: must be a finite number >= 0, got {}", o->gamma));
        auto specs = o->selection.select();
        if (!specs) return report_error(specs.error().message);
        auto context = Context::create({o->device, o->validation});
        if (!context) return report_error(context.error().message);

        StressOptions options{*specs, o->seed, static_cast<float>(o->gamma)};
        bench::Progress progress(fmt::format("stress on {},", (*context)->device_name()), specs->size());
        auto run = run_stress(**context, options, [&](std::size_t, std::size_t, const std::string& name) {
            progress.advance(name);
        });
        if (!run) return report_error(run.error().message);
        for (const std::string& message : (*context)->validation_messages()) std::cerr << "validation: " << message << "\n";

        if (!o->out.empty()) {
            StressReportContext report{bench::utc_now_iso8601(), bench::source_commit(), bench::machine_description(),
                                       "", o->seed, static_cast<float>(o->gamma)};
            report.command = fmt::format("kdop stress --seed {} --gamma {} ({} variants)", o->seed, o->gamma, specs->size());
            const std::filesystem::path dir = o->out;
            if (auto ok = write_files_atomically({{dir / "stress.csv", stress_csv(*run)},
                                                  {dir / "report.md", stress_report_markdown(*run, report)}});
                !ok)
                return report_error(ok.error().message);
        }
        std::cout << fmt::format("kdop stress: {} variants x {} cases on {} ({}), seed {}\n\n", run->variants.size(),
                                 run->cases.size(), run->device_name, run->driver_info, o->seed)
                  << stress_table_text(*run);
        return run->failing_cells() ? 2 : 0;
    };
}

} // namespace kdop::cli
