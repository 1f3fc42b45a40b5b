#include "accuracy/accuracy_report.h"

#include "accuracy/accuracy_charts.h"
#include "core/builtin_sets.h"
#include "core/escaped_text.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace kdop {
namespace {

// Numbers in the report's sentences, as the tables show them.
std::string cell(double value) { return format_value(value, Shown::significant, 3); }

// A family's rows of the trade table, with the lavapipe cost the bench measured where it did.
std::string family_table(const std::vector<TradeRow>& trade, const std::string& family, bool lavapipe) {
    const Table table = trade_table(trade).rows_where([&](std::size_t r) { return trade[r].family == family; });
    const bool counted = std::any_of(trade.begin(), trade.end(),
                                     [](const TradeRow& r) { return std::isfinite(r.lavapipe.marginal_instr_per_px); });
    std::vector<std::string> columns{"variant", "k", "float_ops"};
    if (lavapipe) columns.push_back(counted ? "marginal_instr_per_px" : "marginal_ms");
    for (const char* c : {"mean_dist", "p95_dist", "max_dist", "false_accept_rate", "volume_ratio", "front_float_ops"})
        columns.push_back(c);
    if (lavapipe) columns.push_back("front_lavapipe");
    return table.markdown(columns);
}

// The clip-n9 variants' mean distance per family, as columns in selection order, with each over
// the RGB AABB: what YCoCg and each k-DOP gain on that content.
std::string clip_n9_summary(const std::vector<TradeRow>& trade) {
    // One column per clip-n9 variant measured (of any form and numerics), in selection order.
    std::vector<VariantKey> keys;
    for (const TradeRow& r : trade)
        if (r.key.mode == Mode::clip && r.key.neighborhood == Neighborhood::n9 &&
            std::ranges::find(keys, r.key) == keys.end())
            keys.push_back(r.key);
    if (keys.empty()) return "No clip-n9 variant was measured.\n";
    const bool plain = std::ranges::all_of(
        keys, [](const VariantKey& k) { return k.form == Form::unrolled && k.numerics == Numerics::hardened; });
    std::vector<Column> columns{{"family", "", Shown::text}};
    for (const VariantKey& k : keys) columns.push_back({plain ? k.set : k.name(), "", Shown::text});
    Table table(std::move(columns));
    for (const std::string& family : trade_families(trade)) {
        std::vector<Value> row{family};
        for (const VariantKey& k : keys) {
            const TradeRow* r = find_trade_row(trade, family, k);
            const TradeRow* aabb = find_trade_row(trade, family, k.with_set(kRgbBox));
            const bool relative = r && aabb && k.set != kRgbBox && aabb->mean_dist > 0;
            row.push_back(!r ? Value()
                             : Value(cell(r->mean_dist) +
                                     (relative ? fmt::format(" ({})", format_value(r->mean_dist / aabb->mean_dist,
                                                                                   Shown::ratio, 2))
                                               : "")));
        }
        table.add(std::move(row));
    }
    return table.markdown();
}

std::string rgb_axes_check(const AccuracyRun& run) {
    struct Worst {
        Looser device{0, 0}, reference{0, 0};
        std::size_t pairs = 0;
    };
    std::map<std::string, Worst> worst; // by variant
    std::vector<std::string> order;
    std::set<std::string> device_looser; // images where a clip was, on the device
    for (const AccuracyRow& r : run.rows) {
        if (!r.rgb_axes || r.key.set == kRgbBox || !std::isfinite(r.reference_vs_aabb.share)) continue;
        if (!worst.count(r.key.name())) order.push_back(r.key.name());
        if (r.key.mode == Mode::clip && r.vs_aabb.share > 0) device_looser.insert(r.image);
        Worst& w = worst[r.key.name()];
        for (auto [into, from] : {std::pair{&w.device, &r.vs_aabb}, std::pair{&w.reference, &r.reference_vs_aabb}}) {
            into->share = std::max(into->share, from->share);
            into->largest = std::max(into->largest, from->largest);
        }
        ++w.pairs;
    }
    if (order.empty()) return "No variant of a set that contains the X, Y and Z axes was measured beside aabb.\n";
    Table table({{"variant", "", Shown::text},
                 {"pairs", "", Shown::integer},
                 {"reference_looser", "", Shown::percent, 1, "reference: pixels looser"},
                 {"reference_excess", "S", Shown::significant, 3, "by at most"},
                 {"device_looser", "", Shown::percent, 1, "device: pixels looser"},
                 {"device_excess", "S", Shown::significant, 3, "by at most"}});
    for (const std::string& v : order) {
        const Worst& w = worst[v];
        table.add({v, std::int64_t(w.pairs), w.reference.share, w.reference.largest, w.device.share, w.device.largest});
    }
    std::string out = table.markdown();
    std::string images;
    for (const std::string& i : device_looser) images += (images.empty() ? "" : ", ") + markdown_text(i);
    out += fmt::format("\nClips looser than aabb on the device: {}.\n", images.empty() ? "none" : images);
    return out;
}

std::string sixteen_dop_check(const std::vector<TradeRow>& trade) {
    std::string out;
    std::vector<VariantKey> seen;
    for (const TradeRow& row : trade) {
        const VariantKey grass = row.key.with_set("dop16-grass"), asphalt = row.key.with_set("dop16-asphalt");
        if (row.key != grass || std::ranges::find(seen, grass) != seen.end()) continue;
        seen.push_back(grass);
        std::vector<std::string> grass_wins, asphalt_wins;
        for (const std::string& family : trade_families(trade)) {
            const TradeRow* g = find_trade_row(trade, family, grass);
            const TradeRow* a = find_trade_row(trade, family, asphalt);
            if (!g || !a) continue;
            (g->mean_dist <= a->mean_dist ? grass_wins : asphalt_wins)
                .push_back(fmt::format("{} ({} vs {})", markdown_text(family),
                                       cell(std::min(g->mean_dist, a->mean_dist)),
                                       cell(std::max(g->mean_dist, a->mean_dist))));
        }
        if (grass_wins.empty() && asphalt_wins.empty()) continue;
        const auto list = [](const std::vector<std::string>& v) {
            std::string s;
            for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
            return s.empty() ? std::string("none") : s;
        };
        out += fmt::format("- {} and {}: dop16-grass is the tighter on {}; dop16-asphalt on {}.\n", grass.name(),
                           asphalt.name(), list(grass_wins), list(asphalt_wins));
    }
    // Said of what was measured: one of the two alone, or neither.
    if (!out.empty()) return out;
    bool grass = false, asphalt = false;
    for (const TradeRow& row : trade) {
        grass = grass || row.key.set == "dop16-grass";
        asphalt = asphalt || row.key.set == "dop16-asphalt";
    }
    if (grass != asphalt)
        return fmt::format("Only {} was measured; the comparison needs dop16-grass and dop16-asphalt in the same "
                           "modes and neighborhoods.\n",
                           grass ? "dop16-grass" : "dop16-asphalt");
    return grass ? "dop16-grass and dop16-asphalt were measured in no common mode and neighborhood.\n"
                 : "Neither scene-optimized 16-DOP was measured.\n";
}

} // namespace

std::string accuracy_report_markdown(const AccuracyRun& run, const std::vector<TradeRow>& trade,
                                     const RunMetadata& run_info, const AccuracyReportSettings& c) {
    const bool lavapipe = has_lavapipe_cost(trade);
    double float_error = 0, gpu_ref_mean_gap = 0;
    std::string float_error_at;
    std::set<std::string> pairs;
    for (const AccuracyRow& r : run.rows) {
        if (r.gpu_reference_max > float_error) float_error_at = r.key.name() + " on " + r.image;
        float_error = std::max(float_error, r.gpu_reference_max);
        gpu_ref_mean_gap = std::max(gpu_ref_mean_gap, std::abs(r.gpu.mean_dist - r.reference.mean_dist));
        pairs.insert(r.image);
    }
    std::string out = "# kdop accuracy\n\n" + metadata_markdown(run_info);
    out +=
        fmt::format("- content: {} image pairs in {} families; variance-clip gamma {}; volume ratio on up to {} pixels "
                    "per pair and neighborhood\n",
                    pairs.size(), trade_families(trade).size(), c.gamma, c.volume_samples);
    out += fmt::format("- cost: float ops from the built SPIR-V{}\n\n",
                       c.cost_source.empty() ? "; no lavapipe figures (pass `--cost` a `kdop bench` cost.csv)"
                                             : fmt::format("; lavapipe from `{}`", c.cost_source));

    out +=
        "## What the numbers are\n\n"
        "- **ideal clip**: the largest t in [0, 1] with current + t (history − current) inside the convex hull of the "
        "neighborhood's colors, an LP solved exactly (GLPK's rational simplex; `accuracy/ideal_clip.h`).\n"
        "- **dist**: |variant's color − ideal clipped color| / S, Euclidean in linear RGB, per pixel, with S = max(1, "
        "|current|∞) (so plain linear RGB for content within [0, 1], and HDR highlights relative to their brightness); "
        "mean, p95 (nearest "
        "rank) and max over the pair's pixels. In a family table: the mean of the pairs' means and p95s, the largest "
        "max.\n"
        "- **false accept**: of the histories more than 1e-4 S beyond the hull along the ray, "
        "the share the variant returned unchanged (within 1e-5 S).\n"
        "- **k-DOP / hull volume**: the median over sampled pixels whose hull is solid (volume at least 1e-6 of its "
        "bounding cube), of the padded k-DOP's volume over the hull's (Qhull). Variance clips are not bounding "
        "volumes: below 1 they cut into the hull.\n"
        "- **Pareto front**: no other variant of the family and neighborhood is at most as costly and at most as far "
        "from the ideal (mean dist), and better in one. A variant off the front is never worth it on that content. "
        "n5 and n9 variants are measured against the hulls of their own neighborhoods, so each has its own front.\n";
    out += fmt::format("- The figures are the device's. The double-precision CPU reference (`ref_*` in accuracy.csv) "
                       "gives the same clip without float error: the device differs from it by at most {} S per "
                       "pixel ({}), and the mean distances by at most {}.\n\n",
                       cell(float_error), float_error_at, cell(gpu_ref_mean_gap));

    out +=
        "## Findings\n\n### Mean distance of the clip-n9 variants, and over the RGB AABB\n\n" + clip_n9_summary(trade);
    out += "\n### Scene-optimized 16-DOPs\n\n" + sixteen_dop_check(trade);
    out +=
        "\n### Sets that contain the RGB axes are never looser than the RGB AABB\n\nTheir k-DOP lies inside the "
        "AABB, so in exact arithmetic their clip can only be closer to the ideal. The largest share of a pair's pixels "
        "where a "
        "variant was farther from the ideal than aabb of the same mode and neighborhood by more than 1e-6 S, and the "
        "largest excess, over all pairs. The reference computes in double precision; the device's excess is float32 "
        "rounding: a slab bound carries an error relative to the brightest color projected on it, a ray nearly "
        "parallel to the slab turns that into a long step, and the padding, which follows the pixel's own "
        "magnitude, cannot cover it where a dim pixel neighbors a bright one. Variance clips have no such "
        "guarantee: their slabs are not bounds.\n\n" +
        rgb_axes_check(run);

    out += "\n## By family\n\n";
    if (lavapipe) out += fmt::format("The lavapipe column: {}.\n\n", lavapipe_label(trade));
    const std::vector<std::string> families = trade_families(trade), charts = accuracy_chart_names(trade);
    for (std::size_t f = 0; f < families.size(); ++f) {
        const std::string& family = families[f];
        out += fmt::format("### {}\n\n", markdown_text(family));
        if (c.charts)
            out += fmt::format("![Accuracy against cost on {}]({})\n\n", markdown_text(family),
                               markdown_destination(charts[f]));
        out += family_table(trade, family, lavapipe) + "\n";
    }
    return out;
}

} // namespace kdop
