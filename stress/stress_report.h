// What `kdop stress` prints and writes: the table of variants x cases (a cell is "ok" or the codes
// of the invariants that failed there), stress.csv with every tally, and report.md with the
// table, the legends and the first violation of each failing cell.
#pragma once

#include "stress_suite.h"

#include <string>

namespace kdop {

// For a terminal: cases are numbered columns, named in a legend below the table.
std::string stress_table_text(const StressRun& run);

// One row per variant and case: pixels, and per invariant checked, violated and worst distance.
std::string stress_csv(const StressRun& run);

struct StressReportContext {
    std::string date, commit, machine, command;
    std::uint64_t seed;
    float gamma;
};

std::string stress_report_markdown(const StressRun& run, const StressReportContext& context);

} // namespace kdop
