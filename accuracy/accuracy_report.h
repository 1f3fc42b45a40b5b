// What `kdop accuracy` writes: accuracy.csv (one row per variant and image pair), trade.csv and
// report.md (accuracy per texture family beside the cost the bench measured, with the Pareto
// front marked), and one Pareto chart per family (gnuplot).
#pragma once

#include "accuracy_run.h"
#include "write_files.h"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace kdop {

std::string accuracy_csv(const AccuracyRun& run);

// What `kdop bench` measured on lavapipe for a variant, beyond its gather-only baseline.
struct LavapipeCost {
    double marginal_instr_per_px = NAN; // callgrind: instr_per_px minus gather-<neighborhood>'s
    double marginal_ms = NAN;           // marginal_ms (a median: noisy)
};
// Reads a bench cost.csv (bench/README.md). Errors name the file and line.
Result<std::map<std::string, LavapipeCost>> read_bench_costs(const std::filesystem::path& cost_csv);

// One variant on one family: its accuracy averaged over the family's pairs, beside its cost.
struct TradeRow {
    std::string family, variant, axis_set, mode, neighborhood;
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

std::vector<TradeRow> trade_rows(const AccuracyRun& run, const std::map<std::string, LavapipeCost>& costs);
std::string trade_csv(const std::vector<TradeRow>& rows);

struct AccuracyReportContext {
    std::string date, commit, machine, command;
    std::string cost_source; // the bench cost.csv used, or empty
    std::uint64_t seed = 1;
    float gamma = 1.0f;
    std::size_t volume_samples = 0;
};

std::string accuracy_report_markdown(const AccuracyRun& run, const std::vector<TradeRow>& trade,
                                     const AccuracyReportContext& context);

// pareto-<family>.png for each family, in the order the report shows them.
std::vector<std::string> accuracy_chart_names(const std::vector<TradeRow>& trade);
Result<std::vector<OutputFile>> accuracy_charts(const std::vector<TradeRow>& trade, const std::filesystem::path& scratch,
                                                const std::filesystem::path& out_dir);

} // namespace kdop
