#include "cost_table.h"

#include <fmt/format.h>

#include <cmath>

namespace kdop::bench {
namespace {

std::string field(double value, int decimals) {
    return std::isfinite(value) ? fmt::format("{:.{}f}", value, decimals) : std::string();
}

} // namespace

std::string cost_csv(const std::vector<CostRow>& rows) {
    std::string out = "variant,axis_set,mode,neighborhood,k,spirv_instructions,float_ops,mul,add_sub,fma,min_max,div,"
                      "compare_select,other_float,baseline_float_ops,analytic_min_ops,ms_median,ms_spread,"
                      "baseline_ms_median,marginal_ms,ms_vs_aabb,instr_per_px,baseline_instr_per_px,paper_float_ops,"
                      "paper_ms_median,paper_instr_per_px\n";
    for (const CostRow& r : rows) {
        const FloatOps& f = r.float_ops;
        out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r.variant, r.axis_set,
                           r.mode, r.neighborhood, r.k ? std::to_string(r.k) : "", r.spirv_instructions, f.total(), f.mul,
                           f.add_sub, f.fma, f.min_max, f.div, f.compare_select, f.other, field(r.baseline_float_ops, 0),
                           field(r.analytic_min_ops, 0), field(r.ms_median, 3), field(r.ms_spread, 3),
                           field(r.baseline_ms_median, 3), field(r.marginal_ms, 3), field(r.ms_vs_aabb, 3),
                           field(r.instr_per_px, 1), field(r.baseline_instr_per_px, 1), field(r.paper_float_ops, 0),
                           field(r.paper_ms_median, 3), field(r.paper_instr_per_px, 1));
    }
    return out;
}

} // namespace kdop::bench
