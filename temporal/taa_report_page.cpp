#include "temporal/taa_report_page.h"

#include "core/escaped_text.h"
#include "temporal/ghosting_picture.h"
#include "temporal/report_page/report_page_assets.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace kdop {
namespace {

// An image beside the page, by its path relative to the page.
std::string image(const std::string& path, const std::string& alt) {
    return fmt::format("<img src=\"{}\" alt=\"{}\">", html_text(url_path(path)), html_text(alt));
}

// The table taa.csv holds, sortable by the script (each number cell carries its full value in
// data-value) and sorted by `sorted_by` to begin with, every column but the variant key's parts
// (the variant's name says them), the medians and the intervals (report.md leaves them out too), so
// that it fits a 1400-pixel page.
std::string results_table(const Table& table, const std::string& sorted_by) {
    static const std::vector<std::string> left_out{"axis_set", "mode",     "neighborhood",
                                                   "form",     "numerics", "ghosting_noise"};
    auto left_out_figure = [](std::string_view name) { // every metric's median and interval
        return name.ends_with("_median") || name.ends_with("_low") || name.ends_with("_high");
    };
    std::vector<std::size_t> shown;
    for (std::size_t c = 0; c < table.columns().size(); ++c) {
        const std::string& name = table.columns()[c].name;
        if (std::find(left_out.begin(), left_out.end(), name) == left_out.end() && !left_out_figure(name))
            shown.push_back(c);
    }
    std::string html = "<div class=\"table-wrap\"><table class=\"results\" id=\"results\">\n<thead><tr>";
    for (std::size_t c : shown) {
        const Column& column = table.columns()[c];
        const std::string unit = column.unit.empty() || column.unit == "FLIP" ? "" : " (" + column.unit + ")";
        const std::string title = (column.title.empty() ? column.name : column.title) + unit;
        html += fmt::format("<th title=\"{}\"{}>{}</th>",
                            html_text(column.name + (column.unit.empty() ? "" : ", " + column.unit)),
                            column.name == sorted_by ? " aria-sort=\"ascending\"" : "", html_text(title));
    }
    html += "</tr></thead>\n<tbody>\n";
    for (std::size_t r = 0; r < table.rows().size(); ++r) {
        html += "<tr>";
        for (std::size_t c : shown) {
            const Shown shown_as = table.columns()[c].shown;
            const double number = table.number(r, table.columns()[c].name);
            if (shown_as == Shown::text || shown_as == Shown::flag)
                html += fmt::format("<td>{}</td>", html_text(table.shown(r, c)));
            else
                html += fmt::format("<td class=\"number\" data-value=\"{}\">{}</td>",
                                    std::isnan(number) ? std::string() : fmt::format("{}", number),
                                    html_text(table.shown(r, c)));
        }
        html += "</tr>\n";
    }
    return html + "</tbody></table></div>\n";
}

// `rows` by their ghosting, least first, as report.md orders each scene's (those without a ghosting
// figure last, by their shimmer).
std::vector<TaaRow> least_ghosting_first(std::vector<TaaRow> rows) {
    auto rank = [](const TaaRow& r) {
        const double ghosting = r.mean(kGhosting), shimmer = r.mean(kShimmer);
        return std::pair(std::isnan(ghosting) ? INFINITY : ghosting, std::isnan(shimmer) ? INFINITY : shimmer);
    };
    std::stable_sort(rows.begin(), rows.end(), [&](const TaaRow& a, const TaaRow& b) { return rank(a) < rank(b); });
    return rows;
}

// The viewer's data: the variants, and per sequence its kept frames, worst frames and figures
// (null where there is none).
nlohmann::ordered_json viewer_json(const std::vector<std::string>& variants, const std::vector<ViewerSequence>& viewer,
                                   const std::vector<TaaRow>& rows) {
    nlohmann::ordered_json sequences = nlohmann::ordered_json::array();
    for (const ViewerSequence& s : viewer) {
        if (s.frames.empty()) continue;
        nlohmann::ordered_json worst = nlohmann::ordered_json::array(), figures = nlohmann::ordered_json::array();
        for (std::size_t frame : s.worst)
            worst.push_back(frame == ViewerSequence::kNone ? nlohmann::ordered_json() : nlohmann::ordered_json(frame));
        for (const std::vector<double>& on_frame : s.figures) {
            nlohmann::ordered_json row = nlohmann::ordered_json::array();
            for (double figure : on_frame)
                row.push_back(std::isnan(figure) ? nlohmann::ordered_json() : nlohmann::ordered_json(figure));
            figures.push_back(std::move(row));
        }
        // Each variant's mean figure over the sequence (its taa.csv row's), which the viewer opens
        // on: the best variant against the worst, at the worst one's worst frame.
        nlohmann::ordered_json means = nlohmann::ordered_json::array();
        for (std::size_t v = 0; v < s.variants && v < variants.size(); ++v) {
            const std::string& variant = variants[v];
            double mean = NAN;
            for (const TaaRow& r : rows)
                if (r.scene == s.scene && r.key.name() == variant) mean = r.mean(s.figure);
            means.push_back(std::isnan(mean) ? nlohmann::ordered_json() : nlohmann::ordered_json(mean));
        }
        sequences.push_back({{"name", s.name},
                             {"scene", s.scene},
                             {"figure", s.figure == kGhosting ? "ghosting" : "shimmer"},
                             {"truth", s.truth},
                             {"map", s.map},
                             {"width", s.width},
                             {"height", s.height},
                             {"variants", s.variants},
                             {"frames", s.frames},
                             {"worst", std::move(worst)},
                             {"figures", std::move(figures)},
                             {"means", std::move(means)}});
    }
    return {{"variants", variants}, {"viewer", std::move(sequences)}};
}

// JSON inside <script>: '<' as \u003c, so no string in it can close the element. Names are valid
// UTF-8 by the time they get here (core/file_name.h); were one not, it is replaced, not the cause
// of a run failing at its very end.
std::string script_json(const nlohmann::ordered_json& json) {
    std::string text = json.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
    std::string safe;
    for (char c : text) safe += c == '<' ? std::string("\\u003c") : std::string(1, c);
    return safe;
}

const char* kViewerControls = R"(<div class="controls">
<label>sequence <select id="sequence"></select></label>
<label><input type="range" id="frame-slider" min="0" value="0"> <span id="frame-label"></span></label>
<span class="note" id="frame-note"></span>
</div>
<div class="controls">
<label>A <select id="variant-a"></select></label>
<label>B <select id="variant-b"></select></label>
<label>show <select id="mode"><option value="side">A and B side by side</option><option value="flip">A or B, flipped with F</option></select></label>
<label>FLIP map <select id="map"><option value="frame">hidden</option><option value="overlay">over the frame</option><option value="map">instead of the frame</option></select></label>
<label>zoom <select id="zoom"><option value="1">1x</option><option value="2">2x</option><option value="4">4x</option></select></label>
</div>
<p class="note">Keys: <kbd>F</kbd> or <kbd>space</kbd> flips between A and B, <kbd>M</kbd> cycles the FLIP map, <kbd>&larr;</kbd> <kbd>&rarr;</kbd> step through the kept frames, <kbd>W</kbd> steps to the next variant's worst frame. <span id="map-caption"></span></p>
<div class="views" id="views"></div>
<p class="note">Each variant's worst frame (a click shows it, that variant as B):</p>
<div class="worst" id="worst"></div>
)";

} // namespace

std::string taa_report_html(const std::vector<TaaRow>& rows, const RunMetadata& run, const TaaReportSettings& s,
                            const std::vector<std::string>& variants, const std::vector<ViewerSequence>& viewer) {
    std::vector<std::string> scenes;
    for (const TaaRow& r : rows)
        if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
    const bool has_viewer =
        std::any_of(viewer.begin(), viewer.end(), [](const ViewerSequence& v) { return !v.frames.empty(); });

    std::string html = R"(<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; img-src 'self' file:; style-src 'unsafe-inline'; script-src 'unsafe-inline'">
<title>kdop taa: ghosting and shimmer</title>
<style>
)";
    html += report_page_style();
    html += "</style>\n</head>\n<body>\n<h1>kdop taa: ghosting and shimmer over TAA sequences</h1>\n";
    html +=
        fmt::format("<p>{} variants over {} scenes and sequences, each variant's TAA resolve measured in LDR-FLIP "
                    "(HDR sequences in HDR-FLIP) at {:.1f} pixels per degree, {}. <a href=\"report.md\">report.md</a> "
                    "explains every column; <a href=\"taa.csv\">taa.csv</a> and "
                    "<a href=\"taa_frames.csv\">taa_frames.csv</a> hold the figures.</p>\n",
                    variants.size(), scenes.size(), s.pixels_per_degree, html_text(describe_resolve(s)));
    html += "<nav><a href=\"#table\">table</a>";
    if (has_viewer) html += "<a href=\"#viewer-section\">frame viewer</a>";
    for (const std::string& scene : scenes)
        html += fmt::format("<a href=\"#scene-{0}\">{1}</a>", html_text(url_path(scene)), html_text(scene));
    html += "</nav>\n";

    html += "<h2 id=\"table\">Every variant on every scene and sequence</h2>\n";
    html += "<p class=\"note\">A click on a column's header sorts by it. Shimmer and ghosting are means over the "
            "measured frames, p95 their 95th percentile; – is a figure the sequence is not meant for.</p>\n";
    html += results_table(taa_table(least_ghosting_first(rows), s.metrics), "ghosting");

    if (has_viewer) {
        html += "<h2 id=\"viewer-section\">Frame viewer</h2>\n";
        html += "<p class=\"note\">The frames kept of each sequence: an even spread and each variant's worst frame "
                "(most ghosting, or most shimmer where the sequence measures only shimmer). The truth is the "
                "reference where the sequence has one, else the aliased frame. HDR frames are shown tone mapped "
                "(at exposure 0) with the tone mapper HDR-FLIP uses.</p>\n";
        html += "<section id=\"viewer\">\n";
        html += kViewerControls;
        html += "</section>\n";
    }

    for (std::size_t i = 0; i < scenes.size(); ++i) {
        html += fmt::format("<h2 id=\"scene-{}\">{}</h2>\n", html_text(url_path(scenes[i])), html_text(scenes[i]));
        for (const auto& [name, content] : s.scene_contents)
            if (name == scenes[i]) html += fmt::format("<p>The scene: {}.</p>\n", html_text(content));
        html += "<div class=\"charts\">\n";
        if (i < s.charts.size()) html += image(s.charts[i], "cost against ghosting and shimmer, " + scenes[i]) + "\n";
        if (i < s.over_time.size())
            html += image(s.over_time[i], "ghosting and shimmer over time, " + scenes[i]) + "\n";
        html += "</div>\n";
        const std::string picture = ghosting_picture_name(scenes[i]);
        if (std::find(s.pictures.begin(), s.pictures.end(), picture) != s.pictures.end())
            html += "<div class=\"pictures\">" + image(picture, "every variant over its FLIP map, " + scenes[i]) +
                    "</div>\n";
    }

    html += "<h2>The run</h2>\n<ul class=\"run\">\n";
    html += fmt::format("<li>command: <code>{}</code></li>\n", html_text(run.command));
    html += fmt::format("<li>kdop {} ({})</li>\n", html_text(run.version), html_text(run.commit));
    html += fmt::format("<li>{}, {}</li>\n", html_text(run.date), html_text(run.machine));
    if (!run.device.empty())
        html += fmt::format("<li>device: {} ({})</li>\n", html_text(run.device), html_text(run.driver));
    if (run.seed) html += fmt::format("<li>seed: {}</li>\n", *run.seed);
    html += "</ul>\n";

    html += "<script type=\"application/json\" id=\"kdop-data\">" + script_json(viewer_json(variants, viewer, rows)) +
            "</script>\n<script>\n";
    html += report_page_script();
    html += "</script>\n</body>\n</html>\n";
    return html;
}

} // namespace kdop
