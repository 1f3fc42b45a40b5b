#include "bench/cost_study.h"

#include "bench/cost_report.h"
#include "harness/gnuplot.h"
#include "harness/output_set.h"
#include "harness/scratch_directory.h"

#include <fmt/format.h>

#include <algorithm>

namespace kdop::bench {

Result<std::vector<VariantKey>> bench_variants(const VariantCatalog& catalog, const std::vector<std::string>& names,
                                               Numerics numerics, const std::string& option) {
    if (names.empty()) return catalog.clip_keys(numerics);
    std::vector<VariantKey> keys;
    for (const std::string& name : names) {
        auto key = parse_variant_key(name, option);
        if (!key) return fail(key.error().message);
        if (!key->is_clip() || key->form != Form::unrolled)
            return fail(fmt::format("{}: '{}' is not a clip in its unrolled form; loop forms and the gather and copy "
                                    "baselines are measured beside every clip",
                                    option, name));
        if (std::ranges::find(keys, *key) != keys.end())
            return fail(fmt::format("{}: '{}' is given twice", option, name));
        if (auto set = catalog.set(key->set, option); !set) return fail(set.error().message);
        keys.push_back(*key);
    }
    return keys;
}

Result<CostStudySummary> cost_study(VariantCatalog& catalog, CostStudyOptions options,
                                    const std::filesystem::path& program_dir) {
    auto outputs = OutputSet::prepare(options.out);
    if (!outputs) return fail(outputs.error().message);
    options.bench.probe = program_dir / "kdop-dispatch-probe";
    if (options.bench.callgrind && !std::filesystem::exists(options.bench.probe))
        return fail(
            fmt::format("{} is missing (it is built with kdop); or pass --no-callgrind", options.bench.probe.string()));
    const bool charts = charts_available(options.charts);
    ScratchDirectory scratch("kdop-bench");
    if (scratch.path.empty()) return fail("cannot create a scratch directory in the temporary directory");
    options.bench.scratch = scratch.path;
    auto context = Context::create({options.bench.device, false});
    if (!context) return fail(context.error().message);

    auto result = run_cost_bench(**context, catalog, options.bench);
    if (!result) return fail(result.error().message);

    const RunMetadata run_info = describe_run(**context);
    ReportSettings settings{options.bench, {}};
    if (charts) {
        // A chart that fails costs the chart, not the run: the data and report are still written.
        auto drawn = cost_charts(*result, run_info.device, scratch.path, outputs->dir());
        if (drawn) {
            settings.charts = cost_chart_names(*result);
            outputs->add(std::move(*drawn));
        } else {
            warn_no_charts(drawn.error().message);
        }
    }
    outputs->add_table("cost", cost_table(result->rows), run_info);
    outputs->add("report.md", cost_report_markdown(*result, run_info, settings));
    if (auto ok = outputs->write(); !ok) return fail(ok.error().message);
    return CostStudySummary{options.bench.variants.size(), outputs->size(), run_info};
}

} // namespace kdop::bench
