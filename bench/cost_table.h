// What the cost bench measured, one row per variant, and the one table every output of it is
// drawn from (cost.csv, cost.json, the report's tables). A figure that was not measured (no loop
// form for a baseline kernel, callgrind skipped) is NaN in memory and empty in the table, never a
// made-up zero.
#pragma once

#include "core/variant_key.h"
#include "generator/spirv_cost.h"
#include "harness/table.h"

#include <cmath>
#include <cstddef>
#include <vector>

namespace kdop::bench {

// A median time with its spread, from one interleaved run.
struct Timing {
    double median = NAN, q1 = NAN, q3 = NAN;  // ms
    double spread() const { return q3 - q1; } // interquartile range
};

struct CostRow {
    VariantKey key;
    unsigned k = 0; // 0 for gather and copy
    std::size_t spirv_instructions = 0;
    FloatOps float_ops;
    double loop_float_ops = NAN;                        // the loop form's, compiled the same way
    double analytic_min_ops = NAN;                      // see generator/analytic_cost.h
    Timing ms, loop_ms, gather_ms;                      // gather_ms: the gather-only kernel of the same neighborhood
    double ms_vs_aabb = NAN;                            // median over aabb's of the same mode and neighborhood
    double instr_per_px = NAN, loop_instr_per_px = NAN; // callgrind, one dispatch
    // The same variant with the paper's numerics: what hardening costs (hardened rows only).
    double paper_float_ops = NAN, paper_instr_per_px = NAN;
    Timing paper_ms;
};

// Whether two timings differ by less than their spreads: such a difference is noise, not a saving.
bool within_noise(const Timing& a, const Timing& b);

// Every row with every figure, derived ones (ratios, marginals, noise flags) included.
Table cost_table(const std::vector<CostRow>& rows);

} // namespace kdop::bench
