// What `kdop stress` prints and writes: the table of variants x cases (a cell is "ok" or the codes
// of the invariants that failed there), the stress table (stress.csv and stress.json) with every
// tally, and report.md with the table, the legends and the first violation of each failing cell.
#pragma once

#include "harness/run_metadata.h"
#include "harness/table.h"
#include "stress/stress_suite.h"

#include <string>

namespace kdop {

// For a terminal: cases are numbered columns, named in a legend below the table.
std::string stress_table_text(const StressRun& run);

// One row per variant and case: pixels, and per invariant checked, violated and worst distance.
Table stress_table(const StressRun& run);

// `run_info` carries the seed; `gamma` is the variance clips'.
std::string stress_report_markdown(const StressRun& run, const RunMetadata& run_info, float gamma);

} // namespace kdop
