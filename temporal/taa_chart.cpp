#include "temporal/taa_chart.h"

#include "harness/chart_style.h"
#include "harness/gnuplot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace kdop {
namespace {

// The scenes and sequences `rows` name, in the order they first name them.
template <class Row>
std::vector<std::string> scenes_of(const std::vector<Row>& rows) {
    std::vector<std::string> scenes;
    for (const Row& r : rows)
        if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
    return scenes;
}

} // namespace

std::vector<std::string> taa_chart_names(const std::vector<TaaRow>& rows) {
    std::vector<std::string> names;
    for (const std::string& scene : scenes_of(rows)) names.push_back(fmt::format("trade-{}.png", scene));
    return names;
}

Result<std::vector<OutputFile>> taa_charts(const std::vector<TaaRow>& rows, const std::filesystem::path& scratch,
                                           const std::filesystem::path& out_dir) {
    const std::vector<std::string> scenes = scenes_of(rows), names = taa_chart_names(rows);
    std::vector<VariantKey> keys;
    for (const TaaRow& r : rows) keys.push_back(r.key);
    const VariantChartStyle style(keys);
    // Autoscaled around the points, with a margin: the variants' times and errors lie close together.
    std::string script =
        gnuplot_terminal(1500, 560) +
        "set grid\nset key outside right top spacing 1.1\nset offsets graph 0.08, graph 0.08, graph 0.08, "
        "graph 0.08\n";
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        std::vector<double> ms, ghosting, shimmer;
        std::string plot[2]; // ghosting, shimmer
        std::vector<std::string> groups;
        const TaaRow* any = nullptr; // what the scene's rows were measured in and against
        for (const TaaRow& r : rows)
            if (r.scene == scenes[s]) {
                any = &r;
                ms.push_back(r.ms);
                ghosting.push_back(r.ghosting);
                shimmer.push_back(r.shimmer);
                if (std::find(groups.begin(), groups.end(), VariantChartStyle::group(r.key)) == groups.end())
                    groups.push_back(VariantChartStyle::group(r.key));
            }
        // One data file per group (its point shape), each point in its family's color.
        for (const std::string& group : groups) {
            std::vector<std::vector<std::string>> points;
            int point = 7;
            for (const TaaRow& r : rows)
                if (r.scene == scenes[s] && VariantChartStyle::group(r.key) == group) {
                    const SeriesLook look = style.look(r.key);
                    point = look.point;
                    points.push_back({gnuplot_number(r.ms), gnuplot_number(r.ghosting), gnuplot_number(r.shimmer),
                                      gnuplot_number(r.ms_q1), gnuplot_number(r.ms_q3),
                                      VariantChartStyle::color_value(look.color)});
                }
            const std::string data = (scratch / fmt::format("trade-{}-{}.dat", s, group)).string();
            if (auto ok = write_text(data, gnuplot_data(points)); !ok) return std::unexpected(ok.error());
            for (int y = 0; y < 2; ++y)
                plot[y] += fmt::format("{0}{1} using 1:{2}:4:5:6 with xerrorbars pt 0 lc rgb variable notitle, {1} "
                                       "using 1:{2}:6 with points pt {3} ps 1.5 lc rgb variable notitle",
                                       plot[y].empty() ? "" : ", ", gnuplot_string(data), 2 + y, point);
        }
        // A panel per figure the scene or sequence is meant for (sequence.json's "measure").
        auto measured = [](const std::vector<double>& v) {
            return std::any_of(v.begin(), v.end(), [](double x) { return !std::isnan(x); });
        };
        const bool panels[2] = {measured(ghosting), measured(shimmer)};
        script += gnuplot_output(scratch, s);
        script += fmt::format("set multiplot layout 1,{} title {}\n", int(panels[0]) + int(panels[1]),
                              gnuplot_string(fmt::format("{}: cost against what a viewer sees, one point per variant "
                                                         "(color: axis set; shape: mode and neighborhood; bars: "
                                                         "Q1..Q3 of the time); lower left is better",
                                                         scenes[s])));
        script += axis_scale('x', ms, "ms, rectification pass on the device (median)", false);
        const char* flip = any && any->range == ColorRange::hdr ? "HDR-FLIP" : "LDR-FLIP";
        const char* against = any && any->ghosting_against == "reference" ? "reference" : "aliased frame";
        const std::string titles[2] = {fmt::format("ghosting (mean {} against the {})", flip, against),
                                       fmt::format("shimmer (mean {} between successive frames)", flip)};
        const std::vector<double>* values[2] = {&ghosting, &shimmer};
        const int last = panels[1] ? 1 : 0; // the panel the legend follows
        for (int y = 0; y < 2; ++y) {
            if (!panels[y]) continue;
            script += axis_scale('y', *values[y], titles[y], false);
            script += fmt::format("plot {}{}\n", plot[y], y == last ? style.key_entries() : "");
        }
        script += "unset multiplot\n";
    }
    return draw_charts(script, names, scratch, out_dir);
}

std::vector<std::string> taa_over_time_chart_names(const std::vector<TaaFrameRow>& rows) {
    std::vector<std::string> names;
    for (const std::string& scene : scenes_of(rows)) names.push_back(fmt::format("over-time-{}.png", scene));
    return names;
}

Result<std::vector<OutputFile>> taa_over_time_charts(const std::vector<TaaFrameRow>& rows,
                                                     const std::filesystem::path& scratch,
                                                     const std::filesystem::path& out_dir) {
    const std::vector<std::string> scenes = scenes_of(rows), names = taa_over_time_chart_names(rows);
    std::string script =
        gnuplot_terminal(1500, 520) + "set grid\nset key outside right top spacing 1.1\nset xlabel 'frame'\n";
    double TaaFrameRow::*figures[2] = {&TaaFrameRow::ghosting, &TaaFrameRow::shimmer};
    const char* titles[2] = {"ghosting (FLIP against the truth of each frame)",
                             "shimmer (FLIP against the previous output)"};
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        std::vector<VariantKey> keys; // the scene's variants, in order
        for (const TaaFrameRow& r : rows)
            if (r.scene == scenes[s] && std::find(keys.begin(), keys.end(), r.key) == keys.end()) keys.push_back(r.key);
        // Each variant a line of its own look: its set's color, its mode and neighborhood's dash and point.
        const VariantChartStyle style(keys);
        std::string plots[2];
        for (int f = 0; f < 2; ++f)
            for (std::size_t v = 0; v < keys.size(); ++v) {
                std::vector<std::vector<std::string>> points;
                for (const TaaFrameRow& r : rows)
                    if (r.scene == scenes[s] && r.key == keys[v] && !std::isnan(r.*figures[f]))
                        points.push_back({std::to_string(r.frame), gnuplot_number(r.*figures[f])});
                if (points.empty()) continue;
                const std::string data = (scratch / fmt::format("over-time-{}-{}-{}.dat", s, f, v)).string();
                if (auto ok = write_text(data, gnuplot_data(points)); !ok) return std::unexpected(ok.error());
                const SeriesLook look = style.look(keys[v]);
                plots[f] +=
                    fmt::format("{}{} using 1:2 with linespoints pt {} ps 0.8 dt {} lw 1.5 lc rgb '{}' title {}",
                                plots[f].empty() ? "" : ", ", gnuplot_string(data), look.point, look.dash, look.color,
                                gnuplot_string(keys[v].name()));
            }
        const int panels = int(!plots[0].empty()) + int(!plots[1].empty());
        script += gnuplot_output(scratch, s);
        script += fmt::format(
            "set multiplot layout 1,{} title {}\n", std::max(panels, 1),
            gnuplot_string(fmt::format("{}: each variant over the measured frames (lower is better)", scenes[s])));
        for (int f = 0; f < 2; ++f) // the key beside the last panel only: the variants are the same
            if (!plots[f].empty())
                script += fmt::format("{}set ylabel '{}'\nplot {}\n",
                                      f == 0 && panels == 2 ? "unset key\n" : "set key outside right top spacing 1.1\n",
                                      titles[f], plots[f]);
        script += "unset multiplot\n";
    }
    return draw_charts(script, names, scratch, out_dir);
}

} // namespace kdop
