// What the cost bench measured, one row per variant, and its CSV form (cost.csv). A figure that
// was not measured (no loop form for a baseline kernel, callgrind skipped) is NaN in memory and an
// empty field in the CSV, never a made-up zero.
#pragma once

#include "spirv_cost.h"

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace kdop::bench {

struct CostRow {
    std::string variant, axis_set, mode, neighborhood; // axis_set empty for gather and copy
    unsigned k = 0;                                    // 0 for gather and copy
    std::size_t spirv_instructions = 0;
    FloatOps float_ops;
    double baseline_float_ops = NAN; // the loop form's, compiled the same way
    double analytic_min_ops = NAN;   // see generator/analytic_cost.h
    double ms_median = NAN, ms_spread = NAN; // at the timing size; spread = interquartile range
    double baseline_ms_median = NAN;         // the loop form's
    double marginal_ms = NAN;                // ms_median minus the gather-only kernel of the same neighborhood
    double ms_vs_aabb = NAN;                 // ms_median over aabb's of the same mode and neighborhood (the
                                             // marginal ratio is meaningless where marginals are within the noise)
    double instr_per_px = NAN, baseline_instr_per_px = NAN; // callgrind, one dispatch
    // The same variant with the paper's numerics (Numerics::paper): what hardening costs.
    double paper_float_ops = NAN, paper_ms_median = NAN, paper_instr_per_px = NAN;
};

// Header and rows; numbers with enough digits to recompute the report's ratios.
std::string cost_csv(const std::vector<CostRow>& rows);

} // namespace kdop::bench
