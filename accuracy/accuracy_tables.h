// `kdop accuracy`'s tables: the accuracy table (one row per variant and image pair) and the trade
// table (accuracy per texture family beside the cost the bench measured, with the Pareto front
// marked), harness Tables written as CSV and JSON by the output set; and what the report and the
// charts read from the trade rows.
#pragma once

#include "accuracy/accuracy_run.h"
#include "bench/cost_csv.h"
#include "harness/table.h"

#include <map>
#include <string>
#include <vector>

namespace kdop {

Table accuracy_table(const AccuracyRun& run);

// One variant on one family: its accuracy averaged over the family's pairs, beside its cost.
struct TradeRow {
    std::string family;
    VariantKey key;
    unsigned k = 0;
    double float_ops = NAN;
    LavapipeCost lavapipe;
    double mean_dist = NAN, p95_dist = NAN; // means over the pairs
    double max_dist = NAN;                  // largest over the pairs
    double false_accept_rate = NAN;         // pooled over the pairs
    double volume_ratio = NAN;              // mean of the pairs' medians
    // On the Pareto front of mean distance against that cost: no other variant of the family and
    // neighborhood is at most as costly and at most as far from the ideal, and better in one.
    bool front_float_ops = false, front_lavapipe = false;
};

std::vector<TradeRow> trade_rows(const AccuracyRun& run, const std::map<VariantKey, LavapipeCost>& costs);
Table trade_table(const std::vector<TradeRow>& rows);

// The families of `trade`, in their first row's order.
std::vector<std::string> trade_families(const std::vector<TradeRow>& trade);
// `key`'s row on `family`, or nullptr.
const TradeRow* find_trade_row(const std::vector<TradeRow>& trade, const std::string& family, const VariantKey& key);
// The lavapipe cost a trade row is placed by: callgrind's marginal count where the bench made
// one, else the marginal median time.
double lavapipe_cost(const TradeRow& r);
bool has_lavapipe_cost(const std::vector<TradeRow>& trade);
// What lavapipe_cost is in `trade`, for headings and axes.
const char* lavapipe_label(const std::vector<TradeRow>& trade);

} // namespace kdop
