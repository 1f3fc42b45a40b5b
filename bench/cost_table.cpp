#include "cost_table.h"

#include "variant_columns.h"

namespace kdop::bench {
namespace {

double ratio(double a, double b) { return std::isfinite(a) && std::isfinite(b) && b != 0 ? a / b : NAN; }

} // namespace

bool within_noise(const Timing& a, const Timing& b) {
    return std::abs(a.median - b.median) <= std::max(a.spread(), b.spread());
}

Table cost_table(const std::vector<CostRow>& rows) {
    Table table(joined(variant_columns(), {
                                              {"numerics", "", Shown::text},
                                              {"k", "", Shown::integer},
                                              {"spirv_instructions", "", Shown::integer, 0, "SPIR-V instructions"},
                                              {"float_ops", "", Shown::integer, 0, "float ops"},
                                              {"mul", "", Shown::integer},
                                              {"add_sub", "", Shown::integer, 0, "add/sub"},
                                              {"fma", "", Shown::integer},
                                              {"min_max", "", Shown::integer, 0, "min/max"},
                                              {"div", "", Shown::integer},
                                              {"compare_select", "", Shown::integer, 0, "cmp/sel"},
                                              {"other_float", "", Shown::integer, 0, "other"},
                                              {"loop_float_ops", "", Shown::integer, 0, "loop form"},
                                              {"float_ops_vs_loop", "", Shown::ratio, 2, "vs loop"},
                                              {"analytic_min_ops", "", Shown::integer, 0, "analytic min"},
                                              {"float_ops_vs_min", "", Shown::ratio, 3, "vs min"},
                                              {"ms_median", "ms", Shown::fixed, 2, "median"},
                                              {"ms_q1", "ms", Shown::fixed, 2, "Q1"},
                                              {"ms_q3", "ms", Shown::fixed, 2, "Q3"},
                                              {"loop_ms_median", "ms", Shown::fixed, 2, "loop form"},
                                              {"loop_ms_q1", "ms", Shown::fixed, 2, "loop Q1"},
                                              {"loop_ms_q3", "ms", Shown::fixed, 2, "loop Q3"},
                                              {"vs_loop_ms_noise", "", Shown::flag, 0, "vs loop within noise"},
                                              {"marginal_ms", "ms", Shown::fixed, 2, "marginal"},
                                              {"marginal_ms_noise", "", Shown::flag, 0, "marginal within noise"},
                                              {"ms_vs_aabb", "", Shown::ratio, 2, "vs aabb"},
                                              {"instr_per_px", "instr/px", Shown::fixed, 1, "callgrind"},
                                              {"loop_instr_per_px", "instr/px", Shown::fixed, 1, "loop form"},
                                              {"instr_vs_loop", "", Shown::ratio, 2, "vs loop"},
                                              {"marginal_instr_per_px", "instr/px", Shown::fixed, 1, "marginal"},
                                              {"paper_float_ops", "", Shown::integer, 0, "paper float ops"},
                                              {"paper_ms_median", "ms", Shown::fixed, 2, "paper median"},
                                              {"paper_instr_per_px", "instr/px", Shown::fixed, 1, "paper callgrind"},
                                              {"instr_vs_paper", "", Shown::ratio, 3, "vs paper"},
                                          }));
    for (const CostRow& r : rows) {
        const FloatOps& f = r.float_ops;
        const bool clip = r.key.is_clip();
        const double ops = double(f.total());
        double gather_instr = NAN;
        for (const CostRow& g : rows)
            if (g.key == gather_key(r.key.neighborhood)) gather_instr = g.instr_per_px;
        table.add(joined(variant_values(r.key),
                         {clip ? Value(to_string(r.key.numerics)) : Value(),
                          clip ? Value(std::int64_t(r.k)) : Value(),
                          std::int64_t(r.spirv_instructions),
                          std::int64_t(f.total()),
                          std::int64_t(f.mul),
                          std::int64_t(f.add_sub),
                          std::int64_t(f.fma),
                          std::int64_t(f.min_max),
                          std::int64_t(f.div),
                          std::int64_t(f.compare_select),
                          std::int64_t(f.other),
                          maybe(r.loop_float_ops),
                          maybe(ratio(ops, r.loop_float_ops)),
                          maybe(r.analytic_min_ops),
                          maybe(ratio(ops, r.analytic_min_ops)),
                          maybe(r.ms.median),
                          maybe(r.ms.q1),
                          maybe(r.ms.q3),
                          maybe(r.loop_ms.median),
                          maybe(r.loop_ms.q1),
                          maybe(r.loop_ms.q3),
                          std::isfinite(r.loop_ms.median) ? Value(within_noise(r.ms, r.loop_ms)) : Value(),
                          clip ? maybe(r.ms.median - r.gather_ms.median) : Value(),
                          clip && std::isfinite(r.gather_ms.median) ? Value(within_noise(r.ms, r.gather_ms)) : Value(),
                          maybe(r.ms_vs_aabb),
                          maybe(r.instr_per_px),
                          maybe(r.loop_instr_per_px),
                          maybe(ratio(r.instr_per_px, r.loop_instr_per_px)),
                          clip ? maybe(r.instr_per_px - gather_instr) : Value(),
                          maybe(r.paper_float_ops),
                          maybe(r.paper_ms.median),
                          maybe(r.paper_instr_per_px),
                          maybe(ratio(r.instr_per_px, r.paper_instr_per_px))}));
    }
    return table;
}

} // namespace kdop::bench
