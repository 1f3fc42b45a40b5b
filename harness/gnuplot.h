// Drawing PNG charts with gnuplot, which runs as a program (it has no library interface). The
// script and its data files stay in a scratch directory; the charts come back as files to write
// with the rest of a report, all or nothing. Charts are optional: `--no-charts` turns them off,
// and without gnuplot a command warns and writes its data and report without them.
#pragma once

#include "core/result.h"
#include "core/write_files.h"

#include <filesystem>
#include <string>
#include <vector>

namespace kdop {

// Whitespace-separated rows for gnuplot's data files.
std::string gnuplot_data(const std::vector<std::vector<std::string>>& table);
// A number for a data file; "NaN" (which gnuplot skips) where it is not finite.
std::string gnuplot_number(double value);

// Whether to draw charts: `wanted` (no --no-charts) and gnuplot in PATH. Where gnuplot is
// missing it says so on stderr, once, when called (before the work, so the user knows early).
bool charts_available(bool wanted);
// Says on stderr that the charts are left out because drawing them failed with `reason`.
void warn_no_charts(const std::string& reason);

Result<void> write_text(const std::filesystem::path& path, const std::string& text);

// Runs `script` (which writes each of `charts` into `scratch`) and returns the charts as files
// for `out_dir`, under the same names.
Result<std::vector<OutputFile>> draw_charts(const std::string& script, const std::vector<std::string>& charts,
                                            const std::filesystem::path& scratch, const std::filesystem::path& out_dir);

} // namespace kdop
