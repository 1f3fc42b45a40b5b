// Drawing PNG charts with gnuplot, which runs as a program (it has no library interface). The
// script and its data files stay in a scratch directory; the charts come back as files to write
// with the rest of a report, all or nothing. Charts are optional: `--no-charts` turns them off,
// and without gnuplot a command warns and writes its data and report without them.
#pragma once

#include "core/result.h"
#include "core/write_files.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

// Whitespace-separated rows for gnuplot's data files.
std::string gnuplot_data(const std::vector<std::vector<std::string>>& table);
// A number for a data file; "NaN" (which gnuplot skips) where it is not finite.
std::string gnuplot_number(double value);

// `text` as a gnuplot string literal that holds exactly it: double-quoted, every byte but letters,
// digits, space and . , : ; ( ) + = / _ - as a three-digit octal escape. A script line is code to
// gnuplot even inside quotes: it runs what stands between backquotes, expands @macros, and ends a
// string at its quote, so a scene named a'.system('touch x').' would run a command; escaped, every
// name, path and title is data. What it shows is the bytes as written (UTF-8 included).
std::string gnuplot_string(std::string_view text);

// The first line of every chart's script: PNG through cairo, `width` x `height` pixels, the house
// font, and text shown as written (noenhanced: "dop16_grass" is no subscript, "{x}" no group).
std::string gnuplot_terminal(int width, int height);

// "set output" for the chart draw_charts returns as charts[index]: a file of kdop's own naming in
// the scratch folder, so no name from outside (a scene's, a sequence's) is ever a path gnuplot
// opens, and its length never matters there.
std::string gnuplot_output(const std::filesystem::path& scratch, std::size_t index);

// Whether to draw charts: `wanted` (no --no-charts) and gnuplot in PATH. Where gnuplot is
// missing it says so on stderr, once, when called (before the work, so the user knows early).
bool charts_available(bool wanted);
// Says on stderr that the charts are left out because drawing them failed with `reason`.
void warn_no_charts(const std::string& reason);

Result<void> write_text(const std::filesystem::path& path, const std::string& text);

// Runs `script` (which writes charts[i] through gnuplot_output(scratch, i)) and returns the charts
// as files for `out_dir`, each under its name in `charts`.
Result<std::vector<OutputFile>> draw_charts(const std::string& script, const std::vector<std::string>& charts,
                                            const std::filesystem::path& scratch, const std::filesystem::path& out_dir);

} // namespace kdop
