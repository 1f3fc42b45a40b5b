// What `kdop accuracy` writes: the accuracy table (one row per variant and image pair), the trade
// table and report.md (accuracy per texture family beside the cost the bench measured, with the
// Pareto front marked), and one Pareto chart per family (gnuplot). Tables are harness Tables,
// written as CSV and JSON by the output set.
#pragma once

#include "accuracy/accuracy_run.h"
#include "core/write_files.h"
#include "harness/run_metadata.h"
#include "harness/table.h"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace kdop {

Table accuracy_table(const AccuracyRun& run);

// What `kdop bench` measured on lavapipe for a variant, beyond its gather-only baseline.
struct LavapipeCost {
    double marginal_instr_per_px = NAN; // callgrind: instr_per_px minus gather-<neighborhood>'s
    double marginal_ms = NAN;           // marginal_ms (a median: noisy)
};
// Reads a bench cost.csv (bench/README.md). Errors name the file and line.
Result<std::map<VariantKey, LavapipeCost>> read_bench_costs(const std::filesystem::path& cost_csv);

// One variant on one family: its accuracy averaged over the family's pairs, beside its cost.
struct TradeRow {
    std::string family;
    VariantKey key;
    unsigned k = 0;
    double float_ops = NAN;
    LavapipeCost lavapipe;
    double mean_dist = NAN, p95_dist = NAN; // means over the pairs
    double max_dist = NAN;                  // largest over the pairs
    double false_accept_rate = NAN;         // pooled over the pairs
    double volume_ratio = NAN;              // mean of the pairs' medians
    // On the Pareto front of mean distance against that cost: no other variant of the family and
    // neighborhood is at most as costly and at most as far from the ideal, and better in one.
    bool front_float_ops = false, front_lavapipe = false;
};

std::vector<TradeRow> trade_rows(const AccuracyRun& run, const std::map<VariantKey, LavapipeCost>& costs);
Table trade_table(const std::vector<TradeRow>& rows);

struct AccuracyReportSettings {
    std::string cost_source; // the bench cost.csv used, or empty
    float gamma = 1.0f;
    std::size_t volume_samples = 0;
    bool charts = true; // whether the Pareto charts were drawn (and so can be shown)
};

// `run_info` carries the seed.
std::string accuracy_report_markdown(const AccuracyRun& run, const std::vector<TradeRow>& trade,
                                     const RunMetadata& run_info, const AccuracyReportSettings& settings);

// pareto-<family>.png for each family, in the order the report shows them.
std::vector<std::string> accuracy_chart_names(const std::vector<TradeRow>& trade);
Result<std::vector<OutputFile>> accuracy_charts(const std::vector<TradeRow>& trade,
                                                const std::filesystem::path& scratch,
                                                const std::filesystem::path& out_dir);

} // namespace kdop
