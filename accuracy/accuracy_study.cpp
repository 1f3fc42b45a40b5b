#include "accuracy/accuracy_study.h"

#include "accuracy/accuracy_charts.h"
#include "accuracy/accuracy_inputs.h"
#include "accuracy/accuracy_report.h"
#include "accuracy/accuracy_run.h"
#include "accuracy/accuracy_tables.h"
#include "bench/cost_csv.h"
#include "core/memory_budget.h"
#include "harness/device_runner.h"
#include "harness/gnuplot.h"
#include "harness/output_set.h"
#include "harness/progress.h"
#include "harness/scratch_directory.h"

#include <fmt/format.h>

#include <map>
#include <utility>

namespace kdop {
namespace {

Result<std::vector<AccuracyPair>> read_pairs(const AccuracyContent& content) {
    if (content.current.empty() && content.images.empty()) {
        // The built-in content is made whole before the run: 27 pairs of images, and the textures
        // they are made from.
        if (auto ok =
                check_memory(fmt::format("--size {}", content.size), 64 * image_bytes(content.size, content.size));
            !ok)
            return fail(ok.error().message);
        return builtin_pairs(content.size, content.size, content.seed);
    }
    if (!content.images.empty()) return image_pairs(content.images, content.input_space);
    auto pair = given_pair(content.current, content.history, content.input_space);
    if (!pair) return fail(pair.error().message);
    std::vector<AccuracyPair> pairs;
    pairs.push_back(std::move(*pair));
    return pairs;
}

} // namespace

Result<AccuracyStudySummary> accuracy_study(const std::vector<VariantSpec>& specs, VariantCatalog& catalog,
                                            const AccuracyStudyOptions& options) {
    auto outputs = OutputSet::prepare(options.out);
    if (!outputs) return fail(outputs.error().message);
    std::map<VariantKey, LavapipeCost> costs;
    if (!options.cost.empty()) {
        auto read = read_bench_costs(options.cost);
        if (!read) return fail(read.error().message);
        costs = std::move(*read);
    }
    auto pairs = read_pairs(options.content);
    if (!pairs) return fail(pairs.error().message);

    const bool charts = charts_available(options.charts);
    ScratchDirectory scratch("kdop-accuracy");
    if (scratch.path.empty()) return fail("cannot create a scratch directory in the temporary directory");
    auto context = Context::create(options.device);
    if (!context) return fail(context.error().message);

    AccuracyOptions measured{keys_of(specs), options.gamma, options.volume_samples, options.content.seed};
    DeviceRunner runner(**context);
    Progress progress(fmt::format("accuracy of {} variants on {},", specs.size(), (*context)->device_name()),
                      accuracy_steps(measured, pairs->size()));
    auto run = run_accuracy(runner, catalog, measured, *pairs, &progress);
    progress.finish();
    if (!run) return fail(run.error().message);

    AccuracyStudySummary summary{specs.size(), pairs->size(), describe_run(**context), outputs->dir() / "report.md",
                                 (*context)->validation_messages()};
    summary.run.seed = options.content.seed;
    const std::vector<TradeRow> trade = trade_rows(*run, costs);
    // A chart that fails costs the charts, not the run: the data and report are still written.
    auto drawn = charts ? accuracy_charts(trade, scratch.path, outputs->dir())
                        : Result<std::vector<OutputFile>>(std::vector<OutputFile>{});
    if (!drawn) warn_no_charts(drawn.error().message);
    const bool drew = charts && drawn;
    if (drew) outputs->add(std::move(*drawn));
    outputs->add_table("accuracy", accuracy_table(*run), summary.run);
    outputs->add_table("trade", trade_table(trade), summary.run);
    outputs->add("report.md", accuracy_report_markdown(*run, trade, summary.run,
                                                       {options.cost, options.gamma, options.volume_samples, drew}));
    if (auto ok = outputs->write(); !ok) return fail(ok.error().message);
    return summary;
}

} // namespace kdop
