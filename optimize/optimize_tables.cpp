#include "optimize/optimize_tables.h"

#include <fmt/format.h>

#include <cmath>

namespace kdop {
namespace {

template <class Row>
PrintedColumns<Row> cost_columns(bool lavapipe, const ClipCost Row::*cost) {
    PrintedColumns<Row> columns{
        {"float ops (clip, hardened)", 22, [cost](const Row& r) { return fmt::format("{}", (r.*cost).float_ops); }}};
    if (lavapipe)
        columns.push_back({"lavapipe instr/px", 18, [cost](const Row& r) {
                               return fmt::format("{:.1f}", (r.*cost).lavapipe_instructions.value_or(NAN));
                           }});
    return columns;
}

} // namespace

PrintedColumns<AxisCountRow> axis_count_columns(const Metrics& metrics, std::size_t sequences, bool lavapipe) {
    PrintedColumns<AxisCountRow> columns{
        {"axes", 4, [](const AxisCountRow& r) { return fmt::format("{}", r.axes); }},
        {"k", 4, [](const AxisCountRow& r) { return fmt::format("{}", 2 * r.axes); }},
        {"volume", 14, [](const AxisCountRow& r) { return fmt::format("{:.6g}", r.volume); }}};
    for (std::size_t i = 0; i < sequences; ++i)
        for (std::size_t m : ranking_first(metrics)) {
            if (!metrics[m].measured) continue;
            // A sequence not meant for a metric (sequence.json's "measure") has none.
            columns.push_back({metrics[m].name, 12, [i, m](const AxisCountRow& r) {
                                   const double value = r.figures[i][m];
                                   return std::isnan(value) ? std::string("–") : fmt::format("{:.6f}", value);
                               }});
        }
    return columns + cost_columns(lavapipe, &AxisCountRow::cost);
}

PrintedColumns<SparserRow> sparser_columns(bool lavapipe) {
    return PrintedColumns<SparserRow>{
               {"nonzero", 7, [](const SparserRow& r) { return fmt::format("{}", r.nonzero); }},
               {"score", 14, [](const SparserRow& r) { return fmt::format("{:.6g}", r.score); }}} +
           cost_columns(lavapipe, &SparserRow::cost);
}

PrintedColumns<ComparedSet> compared_set_columns(const ComparedSet& fitted, bool with_distance) {
    PrintedColumns<ComparedSet> columns{{"set", -14, [](const ComparedSet& s) { return s.name; }},
                                        {"volume (x this set's)", 23, [fitted](const ComparedSet& s) {
                                             return fmt::format("{:>12.6g} ({:>7.3f}x)", s.score,
                                                                s.score / fitted.score);
                                         }}};
    if (with_distance)
        columns.push_back({"distance (x this set's)", 23,
                           [fitted](const ComparedSet& s) {
                               return fmt::format("{:>12.6g} ({:>7.3f}x)", s.distance, s.distance / fitted.distance);
                           },
                           "  "});
    return columns;
}

} // namespace kdop
