// What `kdop accuracy` writes: the accuracy table (one row per variant and image pair), the trade
// table and report.md (accuracy per texture family beside the cost the bench measured, with the
// Pareto front marked), and one Pareto chart per family (gnuplot). Tables are harness Tables,
// written as CSV and JSON by the output set.
#pragma once

#include "accuracy/accuracy_tables.h"
#include "harness/run_metadata.h"
#include "harness/table.h"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace kdop {

struct AccuracyReportSettings {
    std::string cost_source; // the bench cost.csv used, or empty
    float gamma = 1.0f;
    std::size_t volume_samples = 0;
    bool charts = true; // whether the Pareto charts were drawn (and so can be shown)
};

// `run_info` carries the seed.
std::string accuracy_report_markdown(const AccuracyRun& run, const std::vector<TradeRow>& trade,
                                     const RunMetadata& run_info, const AccuracyReportSettings& settings);

} // namespace kdop
