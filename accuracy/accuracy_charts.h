// `kdop accuracy`'s Pareto charts (gnuplot): per family, each variant's mean distance to the ideal
// clip against its cost, the front marked.
#pragma once

#include "accuracy/accuracy_tables.h"
#include "core/result.h"
#include "core/write_files.h"

#include <filesystem>
#include <string>
#include <vector>

namespace kdop {

// pareto-<family>.png for each family, in the order the report shows them (trade_families): the
// family's name kept to letters, digits, '.', '_' and '-', and a number added where two families
// would keep to one name.
std::vector<std::string> accuracy_chart_names(const std::vector<TradeRow>& trade);

Result<std::vector<OutputFile>> accuracy_charts(const std::vector<TradeRow>& trade,
                                                const std::filesystem::path& scratch,
                                                const std::filesystem::path& out_dir);

} // namespace kdop
