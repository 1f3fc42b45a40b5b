// The cost bench's human-readable output: report.md (the run's metadata, the tables, the analytic
// minimum's derivation) and its PNG charts, drawn by gnuplot from the cost table. Wall times are
// shown with their interquartile range, and a difference within the spread is labeled as noise.
#pragma once

#include "bench/cost_bench.h"
#include "core/write_files.h"
#include "harness/run_metadata.h"

#include <filesystem>
#include <string>
#include <vector>

namespace kdop::bench {

struct ReportSettings {
    BenchOptions options;
    std::vector<std::string> charts; // the charts drawn (cost_chart_names), empty without charts
};

std::string cost_report_markdown(const BenchResult& result, const RunMetadata& run, const ReportSettings& settings);

// Chart file names, relative to the output directory, in the order the report shows them.
std::vector<std::string> cost_chart_names(const BenchResult& result);

// Draws the charts into `scratch` and returns them as files for `out_dir`.
Result<std::vector<OutputFile>> cost_charts(const BenchResult& result, const std::string& device,
                                            const std::filesystem::path& scratch, const std::filesystem::path& out_dir);

} // namespace kdop::bench
