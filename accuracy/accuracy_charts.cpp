#include "accuracy/accuracy_charts.h"

#include "harness/chart_style.h"
#include "harness/gnuplot.h"

#include <fmt/format.h>

#include <algorithm>

namespace kdop {
namespace {

// Family names become file names and gnuplot strings: keep letters, digits, '.', '_' and '-'.
std::string safe_name(const std::string& s) {
    std::string out = s;
    for (char& c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
    return out;
}

} // namespace

std::vector<std::string> accuracy_chart_names(const std::vector<TradeRow>& trade) {
    std::vector<std::string> names;
    for (const std::string& family : trade_families(trade)) {
        // Families that keep to one name (a/x.png and a_x.png) are told apart by a number.
        std::string name = "pareto-" + safe_name(family) + ".png";
        for (int n = 2; std::find(names.begin(), names.end(), name) != names.end(); ++n)
            name = fmt::format("pareto-{}-{}.png", safe_name(family), n);
        names.push_back(name);
    }
    return names;
}

Result<std::vector<OutputFile>> accuracy_charts(const std::vector<TradeRow>& trade,
                                                const std::filesystem::path& scratch,
                                                const std::filesystem::path& out_dir) {
    const bool lavapipe = has_lavapipe_cost(trade);
    const std::vector<std::string> families = trade_families(trade), names = accuracy_chart_names(trade);
    std::vector<VariantKey> keys;
    for (const TradeRow& r : trade) keys.push_back(r.key);
    const VariantChartStyle style(keys);
    std::string script =
        gnuplot_terminal(lavapipe ? 1800 : 1000, 600) + "set grid\nset key outside right top spacing 1.1\n";
    for (std::size_t f = 0; f < families.size(); ++f) {
        const std::string stem = (scratch / fmt::format("family-{}", f)).string();
        std::vector<double> distances;
        for (const TradeRow& r : trade)
            if (r.family == families[f]) distances.push_back(r.mean_dist);
        script += axis_scale('y', distances, "mean distance to the ideal clip");
        script += gnuplot_output(scratch, f);
        script += fmt::format("set multiplot layout 1,{} title {}\n", lavapipe ? 2 : 1,
                              gnuplot_string(fmt::format("{}: accuracy against cost, one point per variant (color: "
                                                         "axis set; shape: mode and neighborhood); black lines: the "
                                                         "Pareto fronts",
                                                         families[f])));
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
                    // One data file per group (its point shape), each point in its set's color.
                    const VariantKey group_key{"", mode, n};
                    std::vector<std::vector<std::string>> points;
                    for (const TradeRow& r : trade)
                        if (r.family == families[f] && r.key.mode == mode && r.key.neighborhood == n)
                            points.push_back({gnuplot_number(axis.cost(r)), gnuplot_number(r.mean_dist),
                                              VariantChartStyle::color_value(style.look(r.key).color)});
                    if (points.empty()) continue;
                    const std::string data =
                        fmt::format("{}-{}-{}.dat", stem, axis.suffix, VariantChartStyle::group(group_key));
                    if (auto ok = write_text(data, gnuplot_data(points)); !ok) return std::unexpected(ok.error());
                    plot += fmt::format("{}{} using 1:2:3 with points pt {} ps 1.5 lc rgb variable notitle",
                                        plot.empty() ? "" : ", ", gnuplot_string(data), style.look(group_key).point);
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
                fronts += fmt::format(", {} using 1:2 with lines dt {} lw 1.5 lc rgb 'black' title 'Pareto front, {}'",
                                      gnuplot_string(data), shape == Neighborhood::n9 ? 2 : 3, to_string(shape));
            }
            script += fmt::format("set xlabel {}\nplot {}{}{}\n", gnuplot_string(axis.label), plot, style.key_entries(),
                                  fronts);
        }
        script += "unset multiplot\n";
    }
    return draw_charts(script, names, scratch, out_dir);
}

} // namespace kdop
