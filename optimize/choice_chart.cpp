#include "optimize/choice_chart.h"

#include "harness/gnuplot.h"

#include <fmt/format.h>

namespace kdop {

Result<std::vector<OutputFile>> choice_chart(const ChooseResult& result, const std::filesystem::path& scratch,
                                             const std::filesystem::path& out_dir) {
    // One data file per kind of point: fitted, built-in, the front (joined), the recommendation.
    std::vector<std::vector<std::string>> fitted, builtin, front, chosen;
    // Columns: float ops, held-out ghosting, name, ghosting on the frames fitted to.
    for (const Candidate& c : result.candidates)
        (c.fitted ? fitted : builtin)
            .push_back({gnuplot_number(double(c.float_ops)), gnuplot_number(c.validation_ghosting),
                        '"' + c.key.name() + '"', gnuplot_number(c.fit_ghosting)});
    for (std::size_t i : pareto_front(result.candidates))
        front.push_back({gnuplot_number(double(result.candidates[i].float_ops)),
                         gnuplot_number(result.candidates[i].validation_ghosting)});
    if (const auto& i = result.recommendation.chosen)
        chosen.push_back({gnuplot_number(double(result.candidates[*i].float_ops)),
                          gnuplot_number(result.candidates[*i].validation_ghosting)});
    std::string plot;
    const std::pair<const char*, const std::vector<std::vector<std::string>>*> files[] = {
        {"fitted", &fitted}, {"builtin", &builtin}, {"front", &front}, {"chosen", &chosen}};
    for (const auto& [name, rows] : files)
        if (auto ok = write_text(scratch / fmt::format("choice-{}.dat", name), gnuplot_data(*rows)); !ok)
            return std::unexpected(ok.error());
    auto data = [&](const char* name) {
        return gnuplot_string((scratch / fmt::format("choice-{}.dat", name)).string());
    };
    if (!front.empty())
        plot += fmt::format("{} using 1:2 with lines lw 2 lc rgb '#999999' title 'Pareto front'", data("front"));
    if (!builtin.empty())
        plot += fmt::format("{}{} using 1:2 with points pt 7 ps 1.6 lc rgb '#1f77b4' title 'built-in set', {} using "
                            "1:2:3 with labels offset 1,0.6 left font 'sans,9' notitle",
                            plot.empty() ? "" : ", ", data("builtin"), data("builtin"));
    // A fitted set's figure on the frames it was fitted to, joined to its held-out one: the gap a
    // figure measured in sample hides.
    if (!fitted.empty())
        plot += fmt::format("{0}{1} using 1:4:(0):($2-$4) with vectors nohead dt 2 lc rgb '#d62728' notitle, {1} "
                            "using 1:4 with points pt 4 ps 1.6 lc rgb '#d62728' title 'fitted set, on its own frames', "
                            "{1} using 1:2 with points pt 5 ps 1.6 lc rgb '#d62728' title 'fitted set, held out', "
                            "{1} using 1:2:3 with labels offset 1,-0.6 left font 'sans,9' notitle",
                            plot.empty() ? "" : ", ", data("fitted"));
    if (!chosen.empty())
        plot += fmt::format("{}{} using 1:2 with points pt 6 ps 4 lw 2 lc rgb 'black' title 'recommended'",
                            plot.empty() ? "" : ", ", data("chosen"));
    const std::string script =
        gnuplot_terminal(1100, 640) + gnuplot_output(scratch, 0) +
        fmt::format(
            "set grid\nset key outside right top\n"
            "set offsets graph 0.05, graph 0.25, graph 0.08, graph 0.08\n"
            "set title 'kdop choose: held-out ghosting against cost, one point per candidate (lower left is better)'\n"
            "set xlabel 'float ops of the hardened clip'\nset ylabel 'ghosting (mean FLIP over the frames)'\nplot {}\n",
            plot);
    return draw_charts(script, {"choice.png"}, scratch, out_dir);
}

} // namespace kdop
