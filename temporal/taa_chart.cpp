#include "temporal/taa_chart.h"

#include "harness/chart_style.h"
#include "harness/gnuplot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>

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

// A metric's panel: what it compares as the title, in a small font over the panel, and its name,
// unit (a FLIP metric's, the rows' FLIP mode) and which way is better as the axis label, short
// enough for a panel of four.
std::string metric_panel(char axis, std::span<const double> values, const Metric& metric, ColorRange range) {
    const std::string unit = !metric.flip ? metric.unit : range == ColorRange::hdr ? "HDR-FLIP" : "LDR-FLIP";
    const std::string label =
        fmt::format("{} ({}, {} is better)", metric.name, unit, metric.higher_is_better ? "higher" : "lower");
    return fmt::format("set title {} font \",9\"\n", gnuplot_string(metric.description)) +
           (values.empty() ? fmt::format("set {}label {}\n", axis, gnuplot_string(label))
                           : axis_scale(axis, values, label, false));
}

// ", upscaled 2x" for a scene whose rows upscale; empty for one that does not.
std::string upscaled(const TaaRow* row) {
    return row && row->upscale != 1 ? fmt::format(", upscaled {:.3g}x", row->upscale) : std::string();
}

} // namespace

std::vector<std::string> taa_chart_names(const std::vector<TaaRow>& rows) {
    std::vector<std::string> names;
    for (const std::string& scene : scenes_of(rows)) names.push_back(fmt::format("trade-{}.png", scene));
    return names;
}

Result<std::vector<OutputFile>> taa_charts(const std::vector<TaaRow>& rows, const Metrics& metrics,
                                           const std::filesystem::path& scratch, const std::filesystem::path& out_dir) {
    const std::vector<std::string> scenes = scenes_of(rows), names = taa_chart_names(rows);
    std::vector<VariantKey> keys; // the timed rows': the others are lines of their own
    for (const TaaRow& r : rows)
        if (std::isfinite(r.ms)) keys.push_back(r.key);
    const VariantChartStyle style(keys);
    // Autoscaled around the points, with a margin: the variants' times and errors lie close together.
    std::string script =
        gnuplot_terminal(1500, 560) +
        "set grid\nset key outside right top spacing 1.1\nset offsets graph 0.08, graph 0.08, graph 0.08, "
        "graph 0.08\n";
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        std::vector<double> ms;
        std::vector<std::vector<double>> values(metrics.size()); // by metric
        std::vector<std::string> plot(metrics.size());
        std::vector<std::string> groups;
        const TaaRow* any = nullptr;        // what the scene's rows were measured in and against
        std::vector<const TaaRow*> untimed; // the spatial-only upscale: a line at its figure, no time
        for (const TaaRow& r : rows)
            if (r.scene == scenes[s]) {
                any = &r;
                for (std::size_t m = 0; m < metrics.size(); ++m) values[m].push_back(r.mean(m));
                if (!std::isfinite(r.ms)) {
                    untimed.push_back(&r);
                    continue;
                }
                ms.push_back(r.ms);
                if (std::find(groups.begin(), groups.end(), VariantChartStyle::group(r.key)) == groups.end())
                    groups.push_back(VariantChartStyle::group(r.key));
            }
        // One data file per group (its point shape), each point in its family's color: ms, Q1, Q3,
        // the color, then each metric's mean.
        for (const std::string& group : groups) {
            std::vector<std::vector<std::string>> points;
            int point = 7;
            for (const TaaRow& r : rows)
                if (r.scene == scenes[s] && std::isfinite(r.ms) && VariantChartStyle::group(r.key) == group) {
                    const SeriesLook look = style.look(r.key);
                    point = look.point;
                    std::vector<std::string> line{gnuplot_number(r.ms), gnuplot_number(r.ms_q1),
                                                  gnuplot_number(r.ms_q3), VariantChartStyle::color_value(look.color)};
                    for (std::size_t m = 0; m < metrics.size(); ++m) line.push_back(gnuplot_number(r.mean(m)));
                    points.push_back(std::move(line));
                }
            const std::string data = (scratch / fmt::format("trade-{}-{}.dat", s, group)).string();
            if (auto ok = write_text(data, gnuplot_data(points)); !ok) return std::unexpected(ok.error());
            for (std::size_t m = 0; m < metrics.size(); ++m)
                plot[m] += fmt::format("{0}{1} using 1:{2}:2:3:4 with xerrorbars pt 0 lc rgb variable notitle, {1} "
                                       "using 1:{2}:4 with points pt {3} ps 1.5 lc rgb variable notitle",
                                       plot[m].empty() ? "" : ", ", gnuplot_string(data), 5 + m, point);
        }
        // Each untimed row a dashed line across the panel, named in the key beside the last one.
        std::string untimed_key;
        for (const TaaRow* r : untimed) {
            for (std::size_t m = 0; m < metrics.size(); ++m)
                if (!std::isnan(r->mean(m)))
                    plot[m] += fmt::format("{}{} with lines dt 2 lw 2 lc rgb 'gray30' notitle",
                                           plot[m].empty() ? "" : ", ", gnuplot_number(r->mean(m)));
            untimed_key += fmt::format(", NaN with lines dt 2 lw 2 lc rgb 'gray30' title {}",
                                       gnuplot_string(r->key.name() + " (no history)"));
        }
        // A panel per metric the scene or sequence measures (sequence.json's "measure", --metrics).
        std::vector<std::size_t> panels;
        for (std::size_t m = 0; m < metrics.size(); ++m)
            if (std::any_of(values[m].begin(), values[m].end(), [](double x) { return !std::isnan(x); }))
                panels.push_back(m);
        script += gnuplot_output(scratch, s);
        script += fmt::format("set multiplot layout 1,{} title {}\n", std::max<std::size_t>(panels.size(), 1),
                              gnuplot_string(fmt::format("{}{}: cost against what a viewer sees, one point per "
                                                         "variant (color: axis set; shape: mode and neighborhood; "
                                                         "bars: Q1..Q3 of the time)",
                                                         scenes[s], upscaled(any))));
        script += axis_scale('x', ms, "ms, rectification pass on the device (median)", false);
        for (std::size_t m : panels) {
            script += metric_panel('y', values[m], metrics[m], any ? any->range : ColorRange::ldr);
            script += fmt::format("plot {}{}\n", plot[m], m == panels.back() ? style.key_entries() + untimed_key : "");
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

Result<std::vector<OutputFile>> taa_over_time_charts(const std::vector<TaaFrameRow>& rows, const Metrics& metrics,
                                                     const std::filesystem::path& scratch,
                                                     const std::filesystem::path& out_dir) {
    const std::vector<std::string> scenes = scenes_of(rows), names = taa_over_time_chart_names(rows);
    std::string script =
        gnuplot_terminal(1500, 520) + "set grid\nset key outside right top spacing 1.1\nset xlabel 'frame'\n";
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        std::vector<VariantKey> keys; // the scene's variants, in order
        for (const TaaFrameRow& r : rows)
            if (r.scene == scenes[s] && std::find(keys.begin(), keys.end(), r.key) == keys.end()) keys.push_back(r.key);
        // Each variant a line of its own look: its set's color, its mode and neighborhood's dash and point.
        const VariantChartStyle style(keys);
        std::vector<std::string> plots(metrics.size());
        ColorRange range = ColorRange::ldr;
        for (std::size_t m = 0; m < metrics.size(); ++m)
            for (std::size_t v = 0; v < keys.size(); ++v) {
                std::vector<std::vector<std::string>> points;
                for (const TaaFrameRow& r : rows)
                    if (r.scene == scenes[s] && r.key == keys[v] && !std::isnan(r.value(m))) {
                        points.push_back({std::to_string(r.frame), gnuplot_number(r.value(m))});
                        range = r.range;
                    }
                if (points.empty()) continue;
                const std::string data = (scratch / fmt::format("over-time-{}-{}-{}.dat", s, m, v)).string();
                if (auto ok = write_text(data, gnuplot_data(points)); !ok) return std::unexpected(ok.error());
                const SeriesLook look = style.look(keys[v]);
                plots[m] +=
                    fmt::format("{}{} using 1:2 with linespoints pt {} ps 0.8 dt {} lw 1.5 lc rgb '{}' title {}",
                                plots[m].empty() ? "" : ", ", gnuplot_string(data), look.point, look.dash, look.color,
                                gnuplot_string(keys[v].name()));
            }
        std::vector<std::size_t> panels;
        for (std::size_t m = 0; m < metrics.size(); ++m)
            if (!plots[m].empty()) panels.push_back(m);
        script += gnuplot_output(scratch, s);
        script += fmt::format("set multiplot layout 1,{} title {}\n", std::max<std::size_t>(panels.size(), 1),
                              gnuplot_string(fmt::format("{}: each variant over the measured frames", scenes[s])));
        for (std::size_t m : panels) // the key beside the last panel only: the variants are the same
            script += fmt::format("{}{}plot {}\n",
                                  m != panels.back() ? "unset key\n" : "set key outside right top spacing 1.1\n",
                                  metric_panel('y', {}, metrics[m], range), plots[m]);
        script += "unset multiplot\n";
    }
    return draw_charts(script, names, scratch, out_dir);
}

} // namespace kdop
