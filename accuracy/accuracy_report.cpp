#include "accuracy/accuracy_report.h"

#include "core/builtin_sets.h"
#include "core/escaped_text.h"
#include "harness/chart_style.h"
#include "harness/csv_reader.h"
#include "harness/declared_table.h"
#include "harness/gnuplot.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace kdop {
namespace {

// Numbers in the report's sentences, as the tables show them.
std::string cell(double value) { return format_value(value, Shown::significant, 3); }

std::vector<std::string> families_of(const std::vector<TradeRow>& trade) {
    std::vector<std::string> families;
    for (const TradeRow& r : trade)
        if (std::find(families.begin(), families.end(), r.family) == families.end()) families.push_back(r.family);
    return families;
}

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

// The lavapipe cost a trade row is placed by: callgrind's marginal count where the bench made
// one, else the marginal median time.
double lavapipe_cost(const TradeRow& r) {
    return std::isfinite(r.lavapipe.marginal_instr_per_px) ? r.lavapipe.marginal_instr_per_px : r.lavapipe.marginal_ms;
}

std::string chart_name(const std::string& family) { return "pareto-" + family + ".png"; }

const TradeRow* find(const std::vector<TradeRow>& trade, const std::string& family, const VariantKey& key) {
    for (const TradeRow& r : trade)
        if (r.family == family && r.key == key) return &r;
    return nullptr;
}

} // namespace

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

Result<std::map<VariantKey, LavapipeCost>> read_bench_costs(const std::filesystem::path& path) {
    auto csv = read_csv(path);
    if (!csv) return fail("--cost: " + csv.error().message);
    const int variant = csv->column("variant"), instr = csv->column("instr_per_px"),
              marginal = csv->column("marginal_ms");
    if (variant < 0 || instr < 0 || marginal < 0)
        return fail(
            fmt::format("{}:1: not a kdop bench cost.csv (needs the columns variant, instr_per_px and marginal_ms)",
                        path.string()));
    struct Raw {
        double instr, marginal_ms;
    };
    std::map<VariantKey, Raw> raw;
    for (std::size_t r = 0; r < csv->rows.size(); ++r) {
        const std::vector<std::string>& f = csv->rows[r];
        const std::string where = fmt::format("{}:{}", path.string(), csv->lines[r]);
        const auto value = [&](int i) -> Result<double> {
            if (f[i].empty()) return NAN; // not measured
            char* end = nullptr;
            const double v = std::strtod(f[i].c_str(), &end);
            if (end != f[i].c_str() + f[i].size())
                return fail(fmt::format("{}: {} is '{}', not a number", where, csv->header[i], f[i]));
            return v;
        };
        auto key = parse_variant_key(f[variant], where);
        if (!key) return std::unexpected(key.error());
        auto i = value(instr);
        if (!i) return std::unexpected(i.error());
        auto m = value(marginal);
        if (!m) return std::unexpected(m.error());
        raw[*key] = {*i, *m};
    }
    std::map<VariantKey, LavapipeCost> costs;
    for (const auto& [key, r] : raw) {
        if (!key.is_clip()) continue;
        const auto gather = raw.find(gather_key(key.neighborhood));
        costs[key] = {gather == raw.end() ? NAN : r.instr - gather->second.instr, r.marginal_ms};
    }
    return costs;
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
    for (const std::string& family : families_of(rows))
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

namespace {

// Family names become file names and gnuplot strings: keep letters, digits, '.', '_' and '-'.
std::string safe_name(const std::string& s) {
    std::string out = s;
    for (char& c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
    return out;
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
    for (const std::string& family : families_of(trade)) {
        std::vector<Value> row{family};
        for (const VariantKey& k : keys) {
            const TradeRow* r = find(trade, family, k);
            const TradeRow* aabb = find(trade, family, k.with_set(kRgbBox));
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
        for (const std::string& family : families_of(trade)) {
            const TradeRow* g = find(trade, family, grass);
            const TradeRow* a = find(trade, family, asphalt);
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
                    pairs.size(), families_of(trade).size(), c.gamma, c.volume_samples);
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
    for (const std::string& family : families_of(trade)) {
        out += fmt::format("### {}\n\n", markdown_text(family));
        if (c.charts)
            out += fmt::format("![Accuracy against cost on {}]({})\n\n", markdown_text(family),
                               markdown_destination(chart_name(safe_name(family))));
        out += family_table(trade, family, lavapipe) + "\n";
    }
    return out;
}

std::vector<std::string> accuracy_chart_names(const std::vector<TradeRow>& trade) {
    std::vector<std::string> names;
    for (const std::string& family : families_of(trade)) names.push_back(chart_name(safe_name(family)));
    return names;
}

Result<std::vector<OutputFile>> accuracy_charts(const std::vector<TradeRow>& trade,
                                                const std::filesystem::path& scratch,
                                                const std::filesystem::path& out_dir) {
    const bool lavapipe = has_lavapipe_cost(trade);
    const std::vector<std::string> families = families_of(trade), names = accuracy_chart_names(trade);
    std::vector<std::string> sets; // in the order rows name them
    for (const TradeRow& r : trade)
        if (std::find(sets.begin(), sets.end(), safe_name(r.key.set)) == sets.end())
            sets.push_back(safe_name(r.key.set));
    const VariantChartStyle style(sets);
    std::string script = fmt::format("set terminal pngcairo size {},600 font 'sans,10'\nset grid\n"
                                     "set key outside right top spacing 1.1\n",
                                     lavapipe ? 1800 : 1000);
    for (std::size_t f = 0; f < families.size(); ++f) {
        const std::string stem = (scratch / safe_name(families[f])).string();
        std::vector<double> distances;
        std::vector<VariantKey> keys;
        for (const TradeRow& r : trade)
            if (r.family == families[f]) {
                distances.push_back(r.mean_dist);
                keys.push_back(r.key);
            }
        script += axis_scale('y', distances, "mean distance to the ideal clip");
        script += fmt::format("set output '{}'\nset multiplot layout 1,{} title '{}: accuracy against cost, one point "
                              "per variant (color: mode and neighborhood; shape: axis set); black lines: the Pareto "
                              "fronts'\n",
                              (scratch / names[f]).string(), lavapipe ? 2 : 1, safe_name(families[f]));
        struct Axis {
            std::string suffix, label;
            double (*cost)(const TradeRow&);
            bool TradeRow::*front;
        };
        std::vector<Axis> axes = {{"float", "float ops per pixel (SPIR-V)",
                                   [](const TradeRow& r) { return r.float_ops; }, &TradeRow::front_float_ops}};
        if (lavapipe) axes.push_back({"lavapipe", lavapipe_label(trade), lavapipe_cost, &TradeRow::front_lavapipe});
        for (const Axis& axis : axes) {
            std::string plot, fronts;
            for (Mode mode : kAllModes)
                for (Neighborhood n : kAllNeighborhoods) {
                    const VariantKey group_key{"", mode, n};
                    std::vector<std::vector<std::string>> points;
                    for (const TradeRow& r : trade)
                        if (r.family == families[f] && r.key.mode == mode && r.key.neighborhood == n)
                            points.push_back({gnuplot_number(axis.cost(r)), gnuplot_number(r.mean_dist),
                                              std::to_string(style.shape(safe_name(r.key.set)))});
                    if (points.empty()) continue;
                    const std::string data =
                        fmt::format("{}-{}-{}.dat", stem, axis.suffix, VariantChartStyle::group(group_key));
                    if (auto ok = write_text(data, gnuplot_data(points)); !ok) return std::unexpected(ok.error());
                    plot += fmt::format("{}'{}' using 1:2:3 with points pt variable ps 1.5 lc rgb '{}' notitle",
                                        plot.empty() ? "" : ", ", data, VariantChartStyle::color(group_key));
                }
            for (Neighborhood shape : kAllNeighborhoods) {
                std::vector<const TradeRow*> members;
                for (const TradeRow& r : trade)
                    if (r.family == families[f] && r.key.neighborhood == shape && r.*axis.front) members.push_back(&r);
                if (members.empty()) continue;
                std::sort(members.begin(), members.end(),
                          [&](const TradeRow* a, const TradeRow* b) { return axis.cost(*a) < axis.cost(*b); });
                std::vector<std::vector<std::string>> front;
                for (const TradeRow* r : members)
                    front.push_back({gnuplot_number(axis.cost(*r)), gnuplot_number(r->mean_dist)});
                const std::string data = fmt::format("{}-{}-front-{}.dat", stem, axis.suffix, to_string(shape));
                if (auto ok = write_text(data, gnuplot_data(front)); !ok) return std::unexpected(ok.error());
                fronts +=
                    fmt::format(", '{}' using 1:2 with lines dt {} lw 1.5 lc rgb 'black' title 'Pareto front, {}'",
                                data, shape == Neighborhood::n9 ? 2 : 3, to_string(shape));
            }
            script += fmt::format("set xlabel '{}'\nplot {}{}{}\n", axis.label, plot, style.key_entries(keys), fronts);
        }
        script += "unset multiplot\n";
    }
    return draw_charts(script, names, scratch, out_dir);
}

} // namespace kdop
