// The cost bench's human-readable output: report.md (machine, driver, date, commit, the tables,
// the analytic minimum's derivation, the targets met or missed) and its PNG charts, drawn by
// gnuplot. gnuplot runs as a program (it has no library interface); its scripts and data stay
// in the scratch directory.
#pragma once

#include "cost_bench.h"
#include "write_files.h"

#include <filesystem>
#include <string>
#include <vector>

namespace kdop::bench {

struct ReportContext {
    std::string date;    // UTC, ISO 8601
    std::string commit;  // git commit of the source tree, or "unknown"
    std::string machine; // CPU model and core count
    std::string command; // the command line that produced the report
    BenchOptions options;
};

std::string cost_report_markdown(const BenchResult& result, const ReportContext& context);

// Chart file names, relative to the output directory, in the order the report shows them.
std::vector<std::string> cost_chart_names(const BenchResult& result);

// Draws the charts into `scratch` and returns them as files for `out_dir`.
Result<std::vector<OutputFile>> cost_charts(const BenchResult& result, const std::filesystem::path& scratch,
                                            const std::filesystem::path& out_dir);

} // namespace kdop::bench
