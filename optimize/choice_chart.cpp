#include "optimize/choice_chart.h"

#include "harness/gnuplot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace kdop {

ChoicePlot choice_plot(const ChooseResult& result, const ChooseOptions& options, const std::filesystem::path& scratch) {
    // One data file per kind of point: fitted, built-in, the front (joined), the recommendation, and
    // those over a --budget-ms.
    std::vector<std::vector<std::string>> fitted, builtin, front, chosen, over;
    const Budget budget{options.budget_ops, options.budget_ms};
    // Columns: float ops, held-out ghosting, name, ghosting on the frames fitted to, the interval's ends.
    for (const Candidate& c : result.candidates) {
        (c.fitted ? fitted : builtin)
            .push_back({gnuplot_number(double(c.float_ops)), gnuplot_number(c.ranked()), '"' + c.key.name() + '"',
                        gnuplot_number(c.ranked_fit()), gnuplot_number(c.interval.low),
                        gnuplot_number(c.interval.high)});
        if (options.budget_ms && !budget.admits(c))
            over.push_back({gnuplot_number(double(c.float_ops)), gnuplot_number(c.ranked())});
    }
    for (std::size_t i : pareto_front(result.candidates))
        front.push_back(
            {gnuplot_number(double(result.candidates[i].float_ops)), gnuplot_number(result.candidates[i].ranked())});
    if (const auto& i = result.recommendation.chosen)
        chosen.push_back(
            {gnuplot_number(double(result.candidates[*i].float_ops)), gnuplot_number(result.candidates[*i].ranked())});
    ChoicePlot out;
    const std::pair<const char*, const std::vector<std::vector<std::string>>*> files[] = {
        {"fitted", &fitted}, {"builtin", &builtin}, {"front", &front}, {"chosen", &chosen}, {"over", &over}};
    for (const auto& [name, rows] : files)
        out.data.emplace_back(fmt::format("choice-{}.dat", name), gnuplot_data(*rows));
    auto data = [&](const char* name) {
        return gnuplot_string((scratch / fmt::format("choice-{}.dat", name)).string());
    };
    // The held-out figure with its interval where there is one (a NaN end would hide the point).
    const bool intervals = std::all_of(result.candidates.begin(), result.candidates.end(),
                                       [](const Candidate& c) { return c.interval.known(); });
    const char* held_out = intervals ? "1:2:5:6 with yerrorbars" : "1:2 with points";
    std::string plot;
    auto add = [&](const std::string& series) { plot += (plot.empty() ? "" : ", ") + series; };
    if (!front.empty())
        add(fmt::format("{} using 1:2 with lines lw 2 lc rgb '#999999' title 'Pareto front'", data("front")));
    if (!builtin.empty())
        add(fmt::format("{0} using {1} pt 7 ps 1.6 lc rgb '#1f77b4' title 'built-in set{2}', {0} using 1:2:3 with "
                        "labels offset 1,0.6 left font 'sans,9' notitle",
                        data("builtin"), held_out,
                        intervals ? fmt::format(" ({:.0f}% interval)", 100 * kChoiceLevel) : ""));
    // A fitted set's figure on the frames it was fitted to, joined to its held-out one: the gap a
    // figure measured in sample hides.
    if (!fitted.empty())
        add(fmt::format("{0} using 1:4:(0):($2-$4) with vectors nohead dt 2 lc rgb '#d62728' notitle, {0} using 1:4 "
                        "with points pt 4 ps 1.6 lc rgb '#d62728' title 'fitted set, on its own frames', {0} using {1} "
                        "pt 5 ps 1.6 lc rgb '#d62728' title 'fitted set, held out', {0} using 1:2:3 with labels offset "
                        "1,-0.6 left font 'sans,9' notitle",
                        data("fitted"), held_out));
    if (!over.empty())
        add(fmt::format("{} using 1:2 with points pt 2 ps 2.4 lw 2 lc rgb '#ff7f0e' title 'over the budget of {:g} ms'",
                        data("over"), *options.budget_ms));
    if (!chosen.empty())
        add(fmt::format("{} using 1:2 with points pt 6 ps 4 lw 2 lc rgb 'black' title 'recommended'", data("chosen")));
    // The budget as a line where the axes have it (float ops across, ghosting up), drawn as data
    // across the candidates' span so that autoscaling takes it in: an arrow at a budget beyond
    // every candidate would fall outside the plot.
    double x_low = INFINITY, x_high = -INFINITY, y_low = INFINITY, y_high = -INFINITY;
    for (const Candidate& c : result.candidates) {
        x_low = std::min(x_low, double(c.float_ops)), x_high = std::max(x_high, double(c.float_ops));
        for (double y : {c.ranked(), c.ranked_fit(), c.interval.low, c.interval.high})
            if (std::isfinite(y)) y_low = std::min(y_low, y), y_high = std::max(y_high, y);
    }
    std::vector<std::vector<std::string>> line;
    std::string line_title;
    if (options.budget_ops && std::isfinite(y_low)) {
        const std::string x = gnuplot_number(double(*options.budget_ops));
        line = {{x, gnuplot_number(y_low)}, {x, gnuplot_number(y_high)}};
        line_title = fmt::format("budget: {} float ops", *options.budget_ops);
    }
    if (options.target_ghosting && std::isfinite(x_low)) {
        const std::string y = gnuplot_number(*options.target_ghosting);
        line = {{gnuplot_number(x_low), y}, {gnuplot_number(x_high), y}};
        line_title = fmt::format("target: ghosting {}", y);
    }
    out.data.emplace_back("choice-budget.dat", gnuplot_data(line));
    if (!line.empty())
        add(fmt::format("{} using 1:2 with lines dt 2 lw 2 lc rgb '#2ca02c' title '{}'", data("budget"), line_title));
    const char* flip = result.range == ColorRange::hdr ? "HDR-FLIP" : "LDR-FLIP";
    out.script =
        gnuplot_terminal(1100, 640) + gnuplot_output(scratch, 0) +
        fmt::format("set grid\nset key outside right top\n"
                    "set offsets graph 0.05, graph 0.25, graph 0.08, graph 0.08\n"
                    "set title 'kdop choose: held-out ghosting against cost, one point per candidate (lower left is "
                    "better)'\n"
                    "set xlabel 'float ops of the hardened clip, as kdop gen counts them'\n"
                    "set ylabel 'ghosting (mean {} over the frames)'\nplot {}\n",
                    flip, plot);
    return out;
}

Result<std::vector<OutputFile>> choice_chart(const ChooseResult& result, const ChooseOptions& options,
                                             const std::filesystem::path& scratch,
                                             const std::filesystem::path& out_dir) {
    const ChoicePlot plot = choice_plot(result, options, scratch);
    for (const auto& [name, text] : plot.data)
        if (auto ok = write_text(scratch / name, text); !ok) return std::unexpected(ok.error());
    return draw_charts(plot.script, {"choice.png"}, scratch, out_dir);
}

} // namespace kdop
