#include "bench/cost_table.h"

#include "harness/declared_table.h"

namespace kdop::bench {
namespace {

double ratio(double a, double b) { return std::isfinite(a) && std::isfinite(b) && b != 0 ? a / b : NAN; }

// The instructions per pixel of the gather baseline of `r`'s neighborhood, NaN where not counted.
double gather_instr_per_px(const CostRow& r, const std::vector<CostRow>& rows) {
    for (const CostRow& g : rows)
        if (g.key == gather_key(r.key.neighborhood)) return g.instr_per_px;
    return NAN;
}

} // namespace

bool within_noise(const Timing& a, const Timing& b) {
    return std::abs(a.median - b.median) <= std::max(a.spread(), b.spread());
}

Table cost_table(const std::vector<CostRow>& rows) {
    using Row = CostRow;
    const DeclaredColumns<Row> columns =
        variant_key_columns<Row>([](const Row& r) -> const VariantKey& { return r.key; }) +
        DeclaredColumns<Row>{
            {{"numerics", "", Shown::text},
             [](const Row& r) { return r.key.is_clip() ? Value(to_string(r.key.numerics)) : Value(); }},
            {{"k", "", Shown::integer},
             [](const Row& r) { return r.key.is_clip() ? Value(std::int64_t(r.k)) : Value(); }},
            {{"spirv_instructions", "", Shown::integer, 0, "SPIR-V instructions"},
             [](const Row& r) { return Value(std::int64_t(r.spirv_instructions)); }},
            {{"float_ops", "", Shown::integer, 0, "float ops"},
             [](const Row& r) { return Value(std::int64_t(r.float_ops.total())); }},
            {{"mul", "", Shown::integer}, [](const Row& r) { return Value(std::int64_t(r.float_ops.mul)); }},
            {{"add_sub", "", Shown::integer, 0, "add/sub"},
             [](const Row& r) { return Value(std::int64_t(r.float_ops.add_sub)); }},
            {{"fma", "", Shown::integer}, [](const Row& r) { return Value(std::int64_t(r.float_ops.fma)); }},
            {{"min_max", "", Shown::integer, 0, "min/max"},
             [](const Row& r) { return Value(std::int64_t(r.float_ops.min_max)); }},
            {{"div", "", Shown::integer}, [](const Row& r) { return Value(std::int64_t(r.float_ops.div)); }},
            {{"compare_select", "", Shown::integer, 0, "cmp/sel"},
             [](const Row& r) { return Value(std::int64_t(r.float_ops.compare_select)); }},
            {{"other_float", "", Shown::integer, 0, "other"},
             [](const Row& r) { return Value(std::int64_t(r.float_ops.other)); }},
            {{"loop_float_ops", "", Shown::integer, 0, "loop form"},
             [](const Row& r) { return maybe(r.loop_float_ops); }},
            {{"float_ops_vs_loop", "", Shown::ratio, 2, "vs loop"},
             [](const Row& r) { return maybe(ratio(double(r.float_ops.total()), r.loop_float_ops)); }},
            {{"analytic_min_ops", "", Shown::integer, 0, "analytic min"},
             [](const Row& r) { return maybe(r.analytic_min_ops); }},
            {{"float_ops_vs_min", "", Shown::ratio, 3, "vs min"},
             [](const Row& r) { return maybe(ratio(double(r.float_ops.total()), r.analytic_min_ops)); }},
            {{"ms_median", "ms", Shown::fixed, 2, "median"}, [](const Row& r) { return maybe(r.ms.median); }},
            {{"ms_q1", "ms", Shown::fixed, 2, "Q1"}, [](const Row& r) { return maybe(r.ms.q1); }},
            {{"ms_q3", "ms", Shown::fixed, 2, "Q3"}, [](const Row& r) { return maybe(r.ms.q3); }},
            {{"loop_ms_median", "ms", Shown::fixed, 2, "loop form"},
             [](const Row& r) { return maybe(r.loop_ms.median); }},
            {{"loop_ms_q1", "ms", Shown::fixed, 2, "loop Q1"}, [](const Row& r) { return maybe(r.loop_ms.q1); }},
            {{"loop_ms_q3", "ms", Shown::fixed, 2, "loop Q3"}, [](const Row& r) { return maybe(r.loop_ms.q3); }},
            {{"vs_loop_ms_noise", "", Shown::flag, 0, "vs loop within noise"},
             [](const Row& r) {
                 return std::isfinite(r.loop_ms.median) ? Value(within_noise(r.ms, r.loop_ms)) : Value();
             }},
            {{"marginal_ms", "ms", Shown::fixed, 2, "marginal"},
             [](const Row& r) { return r.key.is_clip() ? maybe(r.ms.median - r.gather_ms.median) : Value(); }},
            {{"marginal_ms_noise", "", Shown::flag, 0, "marginal within noise"},
             [](const Row& r) {
                 return r.key.is_clip() && std::isfinite(r.gather_ms.median) ? Value(within_noise(r.ms, r.gather_ms))
                                                                             : Value();
             }},
            {{"ms_vs_aabb", "", Shown::ratio, 2, "vs aabb"}, [](const Row& r) { return maybe(r.ms_vs_aabb); }},
            {{"instr_per_px", "instr/px", Shown::fixed, 1, "callgrind"},
             [](const Row& r) { return maybe(r.instr_per_px); }},
            {{"loop_instr_per_px", "instr/px", Shown::fixed, 1, "loop form"},
             [](const Row& r) { return maybe(r.loop_instr_per_px); }},
            {{"instr_vs_loop", "", Shown::ratio, 2, "vs loop"},
             [](const Row& r) { return maybe(ratio(r.instr_per_px, r.loop_instr_per_px)); }},
            {{"marginal_instr_per_px", "instr/px", Shown::fixed, 1, "marginal"},
             [&rows](const Row& r) {
                 return r.key.is_clip() ? maybe(r.instr_per_px - gather_instr_per_px(r, rows)) : Value();
             }},
            {{"paper_float_ops", "", Shown::integer, 0, "paper float ops"},
             [](const Row& r) { return maybe(r.paper_float_ops); }},
            {{"paper_ms_median", "ms", Shown::fixed, 2, "paper median"},
             [](const Row& r) { return maybe(r.paper_ms.median); }},
            {{"paper_instr_per_px", "instr/px", Shown::fixed, 1, "paper callgrind"},
             [](const Row& r) { return maybe(r.paper_instr_per_px); }},
            {{"instr_vs_paper", "", Shown::ratio, 3, "vs paper"},
             [](const Row& r) { return maybe(ratio(r.instr_per_px, r.paper_instr_per_px)); }},
        };
    return declared_table<Row>(columns, rows);
}

} // namespace kdop::bench
