// The charts `kdop taa` draws per scene or sequence: the trade a user reads first, each variant's
// cost (its median time, with Q1..Q3 as a bar) against each metric (temporal/metrics.h) it was
// measured with, a panel each; and each variant's figures over the measured frames,
// where a trail a few frames long shows as a peak the mean hides. Drawn with gnuplot (harness/gnuplot.h) in the shared
// style of variant charts (harness/chart_style.h): color for mode and neighborhood, shape for the axis set.
#pragma once

#include "core/result.h"
#include "core/write_files.h"
#include "temporal/taa_report.h"

#include <filesystem>
#include <string>
#include <vector>

namespace kdop {

// trade-<scene>.png, one per scene in the order the rows first name them.
std::vector<std::string> taa_chart_names(const std::vector<TaaRow>& rows);

// A panel per metric of `metrics` the scene or sequence measures.
Result<std::vector<OutputFile>> taa_charts(const std::vector<TaaRow>& rows, const Metrics& metrics,
                                           const std::filesystem::path& scratch, const std::filesystem::path& out_dir);

// over-time-<scene>.png, one per scene in the order the rows first name them.
std::vector<std::string> taa_over_time_chart_names(const std::vector<TaaFrameRow>& rows);

// A panel per metric the scene or sequence measures, one line per variant, the frame's index across.
Result<std::vector<OutputFile>> taa_over_time_charts(const std::vector<TaaFrameRow>& rows, const Metrics& metrics,
                                                     const std::filesystem::path& scratch,
                                                     const std::filesystem::path& out_dir);

} // namespace kdop
