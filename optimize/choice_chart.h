// choice.png: kdop choose's candidates, held-out ghosting against the clip's float ops, fitted and
// built-in sets told apart (a fitted set's figure on its own frames beside its held-out one), the
// Pareto front joined and the recommendation ringed; drawn with gnuplot (harness/gnuplot.h).
#pragma once

#include "core/result.h"
#include "core/write_files.h"
#include "optimize/choose.h"

#include <filesystem>
#include <vector>

namespace kdop {

// The chart, drawn in `scratch`, as a file for `out_dir`.
Result<std::vector<OutputFile>> choice_chart(const ChooseResult& result, const std::filesystem::path& scratch,
                                             const std::filesystem::path& out_dir);

} // namespace kdop
