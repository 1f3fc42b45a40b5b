// choice.png: kdop choose's candidates, held-out ghosting (with its bootstrap interval) against the
// float ops the generator counts, fitted and built-in sets told apart (a fitted set's figure on its
// own frames beside its held-out one), the Pareto front joined, the recommendation ringed and the
// budget drawn: a line at --budget-ops or --target-ghosting, the candidates over a --budget-ms
// crossed out; drawn with gnuplot (harness/gnuplot.h).
#pragma once

#include "core/result.h"
#include "core/write_files.h"
#include "optimize/choose.h"

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace kdop {

// What choice_chart hands gnuplot: the script, and its data files by name (in `scratch`). Apart so a
// test can read what is drawn.
struct ChoicePlot {
    std::string script;
    std::vector<std::pair<std::string, std::string>> data; // file name, text
};
ChoicePlot choice_plot(const ChooseResult& result, const ChooseOptions& options, const std::filesystem::path& scratch);

// The chart, drawn in `scratch`, as a file for `out_dir`.
Result<std::vector<OutputFile>> choice_chart(const ChooseResult& result, const ChooseOptions& options,
                                             const std::filesystem::path& scratch,
                                             const std::filesystem::path& out_dir);

} // namespace kdop
