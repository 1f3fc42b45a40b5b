#include "accuracy/accuracy_tables.h"

#include "harness/declared_table.h"

#include <algorithm>

namespace kdop {
namespace {

// Marks the rows (indices into `rows`) on the Pareto front of (cost, mean_dist); rows without the
// cost take no part.
template <class Cost, class Mark>
void mark_front(std::vector<TradeRow>& rows, const std::vector<std::size_t>& family, Cost cost, Mark mark) {
    for (std::size_t i : family) {
        if (!std::isfinite(cost(rows[i]))) continue;
        bool dominated = false;
        for (std::size_t j : family) {
            if (j == i || !std::isfinite(cost(rows[j]))) continue;
            const bool no_worse = cost(rows[j]) <= cost(rows[i]) && rows[j].mean_dist <= rows[i].mean_dist;
            const bool better = cost(rows[j]) < cost(rows[i]) || rows[j].mean_dist < rows[i].mean_dist;
            dominated = dominated || (no_worse && better);
        }
        mark(rows[i]) = !dominated;
    }
}

} // namespace

std::vector<std::string> trade_families(const std::vector<TradeRow>& trade) {
    std::vector<std::string> families;
    for (const TradeRow& r : trade)
        if (std::find(families.begin(), families.end(), r.family) == families.end()) families.push_back(r.family);
    return families;
}

const TradeRow* find_trade_row(const std::vector<TradeRow>& trade, const std::string& family, const VariantKey& key) {
    for (const TradeRow& r : trade)
        if (r.family == family && r.key == key) return &r;
    return nullptr;
}

// The lavapipe cost a trade row is placed by: callgrind's marginal count where the bench made
// one, else the marginal median time.
double lavapipe_cost(const TradeRow& r) {
    return std::isfinite(r.lavapipe.marginal_instr_per_px) ? r.lavapipe.marginal_instr_per_px : r.lavapipe.marginal_ms;
}

bool has_lavapipe_cost(const std::vector<TradeRow>& trade) {
    return std::any_of(trade.begin(), trade.end(), [](const TradeRow& r) { return std::isfinite(lavapipe_cost(r)); });
}

const char* lavapipe_label(const std::vector<TradeRow>& trade) {
    const bool counted = std::any_of(trade.begin(), trade.end(),
                                     [](const TradeRow& r) { return std::isfinite(r.lavapipe.marginal_instr_per_px); });
    return counted ? "lavapipe marginal instructions per pixel (callgrind, over the gather)"
                   : "lavapipe marginal ms (median, over the gather)";
}

Table accuracy_table(const AccuracyRun& run) {
    using Row = AccuracyRow;
    const DeclaredColumns<Row> columns =
        variant_key_columns<Row>([](const Row& r) -> const VariantKey& { return r.key; }) +
        DeclaredColumns<Row>{
            {{"k", "", Shown::integer}, [](const Row& r) { return Value(std::int64_t(r.k)); }},
            {{"rgb_axes", "", Shown::flag}, [](const Row& r) { return Value(r.rgb_axes); }},
            {{"float_ops", "", Shown::integer}, [](const Row& r) { return Value(std::int64_t(r.float_ops)); }},
            {{"family", "", Shown::text}, [](const Row& r) { return Value(r.family); }},
            {{"image", "", Shown::text}, [](const Row& r) { return Value(r.image); }},
            // The device's clip (r.gpu) against the ideal one.
            {{"pixels", "", Shown::integer}, [](const Row& r) { return Value(std::int64_t(r.gpu.pixels)); }},
            {{"outside_hull_rate", "", Shown::percent}, [](const Row& r) { return maybe(r.gpu.outside_rate()); }},
            {{"mean_dist", "S"}, [](const Row& r) { return maybe(r.gpu.mean_dist); }},
            {{"p95_dist", "S"}, [](const Row& r) { return maybe(r.gpu.p95_dist); }},
            {{"max_dist", "S"}, [](const Row& r) { return maybe(r.gpu.max_dist); }},
            {{"false_accept_rate", "", Shown::percent}, [](const Row& r) { return maybe(r.gpu.false_accept_rate()); }},
            // The CPU reference's clip (r.reference) against the ideal one.
            {{"ref_mean_dist", "S"}, [](const Row& r) { return maybe(r.reference.mean_dist); }},
            {{"ref_p95_dist", "S"}, [](const Row& r) { return maybe(r.reference.p95_dist); }},
            {{"ref_max_dist", "S"}, [](const Row& r) { return maybe(r.reference.max_dist); }},
            {{"ref_false_accept_rate", "", Shown::percent},
             [](const Row& r) { return maybe(r.reference.false_accept_rate()); }},
            {{"gpu_ref_max_diff", "S"}, [](const Row& r) { return maybe(r.gpu_reference_max); }},
            {{"looser_than_aabb", "", Shown::percent}, [](const Row& r) { return maybe(r.vs_aabb.share); }},
            {{"ref_looser_than_aabb", "", Shown::percent},
             [](const Row& r) { return maybe(r.reference_vs_aabb.share); }},
            {{"max_excess_over_aabb", "S"}, [](const Row& r) { return maybe(r.vs_aabb.largest); }},
            {{"ref_max_excess_over_aabb", "S"}, [](const Row& r) { return maybe(r.reference_vs_aabb.largest); }},
            {{"volume_ratio_median"}, [](const Row& r) { return maybe(r.volume.median); }},
            {{"volume_ratio_mean"}, [](const Row& r) { return maybe(r.volume.mean); }},
            {{"volume_pixels", "", Shown::integer}, [](const Row& r) { return Value(std::int64_t(r.volume.pixels)); }},
        };
    return declared_table<Row>(columns, run.rows);
}

std::vector<TradeRow> trade_rows(const AccuracyRun& run, const std::map<VariantKey, LavapipeCost>& costs) {
    std::vector<TradeRow> rows;
    std::vector<std::size_t> pairs; // pairs averaged into each row
    std::vector<std::size_t> outside, accepted;
    for (const AccuracyRow& a : run.rows) {
        auto it = std::find_if(rows.begin(), rows.end(),
                               [&](const TradeRow& t) { return t.family == a.family && t.key == a.key; });
        if (it == rows.end()) {
            TradeRow t;
            t.family = a.family, t.key = a.key, t.k = a.k, t.float_ops = double(a.float_ops);
            if (auto c = costs.find(a.key); c != costs.end()) t.lavapipe = c->second;
            t.mean_dist = t.p95_dist = t.max_dist = t.volume_ratio = 0;
            rows.push_back(t);
            pairs.push_back(0), outside.push_back(0), accepted.push_back(0);
            it = rows.end() - 1;
        }
        const std::size_t i = static_cast<std::size_t>(it - rows.begin());
        ++pairs[i];
        it->mean_dist += a.gpu.mean_dist;
        it->p95_dist += a.gpu.p95_dist;
        it->max_dist = std::max(it->max_dist, a.gpu.max_dist);
        it->volume_ratio += a.volume.median; // NaN (no sample) stays NaN
        outside[i] += a.gpu.outside;
        accepted[i] += a.gpu.falsely_accepted;
    }
    for (std::size_t i = 0; i < rows.size(); ++i) {
        rows[i].mean_dist /= double(pairs[i]);
        rows[i].p95_dist /= double(pairs[i]);
        rows[i].volume_ratio /= double(pairs[i]);
        rows[i].false_accept_rate = outside[i] ? double(accepted[i]) / double(outside[i]) : NAN;
    }
    // n5 and n9 variants are measured against different hulls (of their own neighborhoods), so
    // each neighborhood has its own front.
    for (const std::string& family : trade_families(rows))
        for (Neighborhood shape : kAllNeighborhoods) {
            std::vector<std::size_t> members;
            for (std::size_t i = 0; i < rows.size(); ++i)
                if (rows[i].family == family && rows[i].key.neighborhood == shape) members.push_back(i);
            mark_front(
                rows, members, [](const TradeRow& r) { return r.float_ops; },
                [](TradeRow& r) -> bool& { return r.front_float_ops; });
            mark_front(rows, members, lavapipe_cost, [](TradeRow& r) -> bool& { return r.front_lavapipe; });
        }
    return rows;
}

Table trade_table(const std::vector<TradeRow>& rows) {
    using Row = TradeRow;
    const DeclaredColumns<Row> columns =
        DeclaredColumns<Row>{{{"family", "", Shown::text}, [](const Row& r) { return Value(r.family); }}} +
        variant_key_columns<Row>([](const Row& r) -> const VariantKey& { return r.key; }) +
        DeclaredColumns<Row>{
            {{"k", "", Shown::integer}, [](const Row& r) { return Value(std::int64_t(r.k)); }},
            {{"float_ops", "", Shown::integer, 0, "float ops"}, [](const Row& r) { return maybe(r.float_ops); }},
            {{"marginal_instr_per_px", "instr/px", Shown::significant, 4, "lavapipe marginal"},
             [](const Row& r) { return maybe(r.lavapipe.marginal_instr_per_px); }},
            {{"marginal_ms", "ms", Shown::fixed, 2, "lavapipe marginal"},
             [](const Row& r) { return maybe(r.lavapipe.marginal_ms); }},
            {{"mean_dist", "S", Shown::significant, 3, "mean dist"}, [](const Row& r) { return maybe(r.mean_dist); }},
            {{"p95_dist", "S", Shown::significant, 3, "p95 dist"}, [](const Row& r) { return maybe(r.p95_dist); }},
            {{"max_dist", "S", Shown::significant, 3, "max dist"}, [](const Row& r) { return maybe(r.max_dist); }},
            {{"false_accept_rate", "", Shown::percent, 1, "false accept"},
             [](const Row& r) { return maybe(r.false_accept_rate); }},
            {{"volume_ratio", "", Shown::significant, 3, "k-DOP / hull volume"},
             [](const Row& r) { return maybe(r.volume_ratio); }},
            {{"front_float_ops", "", Shown::flag, 0, "front (float ops)"},
             [](const Row& r) { return Value(r.front_float_ops); }},
            {{"front_lavapipe", "", Shown::flag, 0, "front (lavapipe)"},
             [](const Row& r) { return std::isfinite(lavapipe_cost(r)) ? Value(r.front_lavapipe) : Value(); }},
        };
    return declared_table<Row>(columns, rows);
}

} // namespace kdop
