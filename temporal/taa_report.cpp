#include "temporal/taa_report.h"

#include "core/escaped_text.h"
#include "harness/declared_table.h"
#include "harness/rank_correlation.h"
#include "temporal/ghosting_picture.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>
#include <optional>
#include <ranges>

namespace kdop {
namespace {

// Ikkala et al. 2024, Tables 1 ("Grass") and 2 ("Asphalt"): method, time on a GTX 1080 Ti (ms),
// shimmer and ghosting (FLIP). "16-DOP+Opt" is the 16-DOP optimized for that scene.
struct PaperRow {
    const char* method;
    VariantKey key;
    double ms, shimmer, ghosting;
};

VariantKey clip_of(const char* set, Mode mode) { return {set, mode, Neighborhood::n9}; }

// Which of the paper's tables a scene stands beside: grass and grass3d Table 1, asphalt and
// asphalt3d Table 2; 0 for none.
int paper_table_number(const std::string& scene) {
    if (scene == "grass" || scene == "grass3d") return 1;
    if (scene == "asphalt" || scene == "asphalt3d") return 2;
    return 0;
}

std::vector<PaperRow> paper_table(const std::string& scene) {
    if (paper_table_number(scene) == 1)
        return {{"RGB", clip_of("aabb", Mode::clip), 0.449, 0.0346, 0.0499},
                {"YCoCg", clip_of("ycocg", Mode::clip), 0.452, 0.0344, 0.0538},
                {"32-DOP", clip_of("dop32", Mode::clip), 0.662, 0.0433, 0.0399},
                {"16-DOP+Opt", clip_of("dop16-grass", Mode::clip), 0.538, 0.0491, 0.0374},
                {"RGB+Var", clip_of("aabb", Mode::varclip), 0.465, 0.0406, 0.0417},
                {"YCoCg+Var", clip_of("ycocg", Mode::varclip), 0.451, 0.0411, 0.0448},
                {"32-DOP+Var", clip_of("dop32", Mode::varclip), 0.665, 0.0568, 0.0336}};
    if (paper_table_number(scene) == 2)
        return {{"RGB", clip_of("aabb", Mode::clip), 0.428, 0.0111, 0.0520},
                {"YCoCg", clip_of("ycocg", Mode::clip), 0.465, 0.0117, 0.0319},
                {"32-DOP", clip_of("dop32", Mode::clip), 0.635, 0.0120, 0.0321},
                {"16-DOP+Opt", clip_of("dop16-asphalt", Mode::clip), 0.528, 0.0130, 0.0300},
                {"RGB+Var", clip_of("aabb", Mode::varclip), 0.466, 0.0116, 0.0439},
                {"YCoCg+Var", clip_of("ycocg", Mode::varclip), 0.466, 0.0134, 0.0289},
                {"32-DOP+Var", clip_of("dop32", Mode::varclip), 0.653, 0.0144, 0.0286}};
    return {};
}

// Rank (1 = smallest) of each value among `values`.
std::vector<int> ranks(const std::vector<double>& values) {
    std::vector<int> out(values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        out[i] = 1 + int(std::count_if(values.begin(), values.end(), [&](double v) { return v < values[i]; }));
    return out;
}

// kdop's figures beside the paper's for the rows both have; empty when the scene is not the paper's
// or the run lacks one of its methods.
std::string paper_comparison(const std::string& scene, const std::vector<TaaRow>& rows) {
    const std::vector<PaperRow> paper = paper_table(scene);
    std::vector<const TaaRow*> ours;
    for (const PaperRow& p : paper) {
        auto it =
            std::find_if(rows.begin(), rows.end(), [&](const TaaRow& r) { return r.scene == scene && r.key == p.key; });
        if (it == rows.end()) return {};
        ours.push_back(&*it);
    }
    if (paper.empty()) return {};
    std::vector<double> ps, pg, os, og;
    for (std::size_t i = 0; i < paper.size(); ++i) {
        ps.push_back(paper[i].shimmer), pg.push_back(paper[i].ghosting);
        os.push_back(ours[i]->mean(kShimmer)), og.push_back(ours[i]->mean(kGhosting));
    }
    const auto rps = ranks(ps), rpg = ranks(pg), ros = ranks(os), rog = ranks(og);
    std::string md =
        fmt::format("Beside Table {} of the paper (rank 1 = least among these seven):\n\n", paper_table_number(scene));
    md += "| method | variant | paper shimmer | kdop shimmer | paper ghosting | kdop ghosting | kdop / paper ghosting "
          "|\n";
    md += "|---|---|--:|--:|--:|--:|--:|\n";
    int within = 0; // methods whose ghosting is within 1.5x of the paper's, either way
    for (std::size_t i = 0; i < paper.size(); ++i) {
        const double ratio = og[i] / pg[i];
        within += ratio >= 1 / 1.5 && ratio <= 1.5;
        md += fmt::format("| {} | {} | {:.4f} (#{}) | {:.4f} (#{}) | {:.4f} (#{}) | {:.4f} (#{}) | {:.2f} |\n",
                          paper[i].method, paper[i].key.name(), ps[i], rps[i], os[i], ros[i], pg[i], rpg[i], og[i],
                          rog[i], ratio);
    }
    md += fmt::format("\nSpearman's rank correlation with the paper's column: shimmer {:.2f}, ghosting {:.2f} (1: the "
                      "same order). Ghosting within 1.5x of the paper's: {} of {} methods.\n",
                      spearman(ps, os), spearman(pg, og), within, paper.size());

    // The orderings the paper's text draws from its tables, side by side.
    auto first = [&](const std::vector<int>& rank, int wanted) {
        std::string names;
        for (std::size_t i = 0; i < rank.size(); ++i)
            if (rank[i] == wanted) names += (names.empty() ? "" : ", ") + std::string(paper[i].method);
        return names;
    };
    const int last = int(paper.size());
    md += fmt::format("\nThe orderings the paper's text draws:\n\n- Least ghosting: paper {}, kdop {}.\n",
                      first(rpg, 1), first(rog, 1));
    md += fmt::format("- Most ghosting: paper {}, kdop {}.\n", first(rpg, last), first(rog, last));
    md += fmt::format("- Least shimmer: paper {}, kdop {}.\n", first(rps, 1), first(ros, 1));
    md += fmt::format("- Most shimmer: paper {}, kdop {}.\n", first(rps, last), first(ros, last));
    // Rows 0 and 1 are RGB and YCoCg: where YCoCg helps is their ratio below 1.
    md += fmt::format("- YCoCg over RGB, ghosting: paper {:.2f}x, kdop {:.2f}x (below 1: YCoCg helps).\n\n",
                      pg[1] / pg[0], og[1] / og[0]);
    return md;
}

// HDR-FLIP's exposures as the run set them, or as each pair's reference gives them.
std::string describe_exposures(const ExposureOptions& o) {
    auto given = [](const std::optional<float>& e, const char* derived) {
        return e ? fmt::format("{:g}", *e) : std::string(derived);
    };
    const std::string count = o.count ? fmt::format("{} exposures", *o.count) : "max(2, ceil(stop - start)) exposures";
    if (!o.start && !o.stop && !o.count)
        return "at the exposures NVlabs/flip derives from each pair's reference (from its largest luminance to its "
               "median)";
    return fmt::format("{} from {} to {}", count, given(o.start, "the one the reference's largest luminance gives"),
                       given(o.stop, "the one the reference's median luminance gives"));
}

// Where each variant's figures are worst, the frames to look at first.
std::string worst_frames(const std::vector<TaaRow>& rows, const Metrics& metrics) {
    std::string md;
    for (const TaaRow& r : rows) {
        std::vector<std::string> worst;
        for (std::size_t m = 0; m < metrics.size() && m < r.figures.size(); ++m)
            if (metrics[m].measured && !r.figures[m].worst_frame.empty())
                worst.push_back(fmt::format("{} {} at {}", metrics[m].higher_is_better ? "least" : "most",
                                            metrics[m].name, markdown_text(r.figures[m].worst_frame)));
        if (!worst.empty()) md += fmt::format("- {}: {}\n", markdown_text(r.key.name()), fmt::join(worst, "; "));
    }
    return md.empty() ? md : "Each variant's worst frames:\n\n" + md + "\n";
}

// The names of the measured metrics in bold, "**a**, **b** and **c**".
std::string measured_names(const Metrics& metrics) {
    std::vector<std::string> names;
    for (const Metric& m : metrics)
        if (m.measured) names.push_back("**" + m.name + "**");
    if (names.size() < 2) return names.empty() ? std::string() : names.front();
    const std::string last = names.back();
    names.pop_back();
    return fmt::format("{} and {}", fmt::join(names, ", "), last);
}

// What each measured metric beyond the paper's two compares, from the registry.
std::string metric_descriptions(const Metrics& metrics) {
    std::string md;
    for (std::size_t m = 0; m < metrics.size(); ++m)
        if (metrics[m].measured && m != kShimmer && m != kGhosting)
            md += fmt::format("- **{}** ({}): {}{}.\n", metrics[m].name, metrics[m].unit, metrics[m].description,
                              metrics[m].needs_reference ? ", where the sequence has reference frames" : "");
    return md;
}

} // namespace

bool within_noise_of_fastest(const TaaRow& row, const std::vector<TaaRow>& rows) {
    const TaaRow* fastest = nullptr;
    for (const TaaRow& r : rows)
        if (std::isfinite(r.ms) && (!fastest || r.ms < fastest->ms)) fastest = &r;
    if (!fastest || !std::isfinite(row.ms)) return false;
    return std::abs(row.ms - fastest->ms) <= std::max(row.ms_q3 - row.ms_q1, fastest->ms_q3 - fastest->ms_q1);
}

Table taa_table(const std::vector<TaaRow>& rows, const Metrics& metrics) {
    DeclaredColumns<TaaRow> columns =
        variant_key_columns<TaaRow>([](const TaaRow& r) -> const VariantKey& { return r.key; }) +
        DeclaredColumns<TaaRow>{{{"scene", "", Shown::text}, [](const TaaRow& r) { return Value(r.scene); }},
                                {{"upscale", "x", Shown::fixed, 2, "output width over input width (1: no upscaling)"},
                                 [](const TaaRow& r) { return Value(r.upscale); }}} +
        time_columns<TaaRow>(&TaaRow::ms, &TaaRow::ms_q1, &TaaRow::ms_q3) +
        DeclaredColumns<TaaRow>{
            {{"ms_noise", "", Shown::flag, 0, "ms within noise of the fastest"}, [&rows](const TaaRow& r) {
                 return std::isfinite(r.ms) ? Value(within_noise_of_fastest(r, rows)) : Value();
             }}};
    // Each measured metric's figures, then its worst frames, all from the registry.
    auto figure = [](std::size_t m, double MetricFigures::*f) {
        return [m, f](const TaaRow& r) { return m < r.figures.size() ? maybe(r.figures[m].*f) : Value(); };
    };
    auto bound = [](std::size_t m, double Interval::*f) {
        return [m, f](const TaaRow& r) { return m < r.figures.size() ? maybe(r.figures[m].interval.*f) : Value(); };
    };
    for (std::size_t m = 0; m < metrics.size(); ++m) {
        const Metric& metric = metrics[m];
        if (!metric.measured) continue;
        const std::string& n = metric.name;
        const int d = metric.digits;
        columns.push_back({{n, metric.unit, Shown::fixed, d, n + " (mean)"}, figure(m, &MetricFigures::mean)});
        columns.push_back(
            {{n + "_median", metric.unit, Shown::fixed, d, n + " median"}, figure(m, &MetricFigures::median)});
        columns.push_back({{n + "_p95", metric.unit, Shown::fixed, d, n + " p95"}, figure(m, &MetricFigures::p95)});
        columns.push_back(
            {{n + "_low", metric.unit, Shown::fixed, d, n + " 95% interval from"}, bound(m, &Interval::low)});
        columns.push_back({{n + "_high", metric.unit, Shown::fixed, d, "to"}, bound(m, &Interval::high)});
    }
    const std::string& ranked = metrics[ranking_first(metrics).front()].name;
    columns.push_back({{ranked + "_noise", "", Shown::flag, 0, ranked + " within noise of the least"},
                       [](const TaaRow& r) { return r.within_noise ? Value(*r.within_noise) : Value(); }});
    for (std::size_t m : ranking_first(metrics))
        if (metrics[m].measured)
            columns.push_back({{"worst_" + metrics[m].name + "_frame", "", Shown::text, 0,
                                fmt::format("{} at", metrics[m].higher_is_better ? "least " + metrics[m].name
                                                                                 : "most " + metrics[m].name)},
                               [m](const TaaRow& r) {
                                   return m < r.figures.size() && !r.figures[m].worst_frame.empty()
                                              ? Value(r.figures[m].worst_frame)
                                              : Value();
                               }});
    columns.push_back({{ranked + "_against", "", Shown::text, 0, ranked + " against"},
                       [](const TaaRow& r) { return std::isnan(r.mean(kGhosting)) ? Value() : Value(r.truth); }});
    columns.push_back({{"flip", "", Shown::text, 0, "measured in"}, [](const TaaRow& r) {
                           return Value(std::string(r.range == ColorRange::hdr ? "HDR-FLIP" : "LDR-FLIP"));
                       }});
    return declared_table<TaaRow>(columns, rows);
}

Table taa_frames_table(const std::vector<TaaFrameRow>& rows, const Metrics& metrics) {
    DeclaredColumns<TaaFrameRow> columns =
        variant_key_columns<TaaFrameRow>([](const TaaFrameRow& r) -> const VariantKey& { return r.key; }) +
        DeclaredColumns<TaaFrameRow>{
            {{"scene", "", Shown::text}, [](const TaaFrameRow& r) { return Value(r.scene); }},
            {{"sequence", "", Shown::text}, [](const TaaFrameRow& r) { return Value(r.sequence); }},
            {{"frame", "", Shown::integer}, [](const TaaFrameRow& r) { return Value(std::int64_t(r.frame)); }},
        };
    for (std::size_t m : ranking_first(metrics))
        if (metrics[m].measured)
            columns.push_back({{metrics[m].name, metrics[m].unit, Shown::fixed, metrics[m].digits},
                               [m](const TaaFrameRow& r) { return maybe(r.value(m)); }});
    return declared_table<TaaFrameRow>(columns, rows);
}

std::string describe_resolve(const TaaReportSettings& s) {
    if (s.own_resolve.empty()) return describe(s.resolve);
    return fmt::format("the resolve {} given to kdop taa --resolve, bound by its map, with a current weight of {:g} "
                       "and a gamma of {:g} where its map asks for them",
                       s.own_resolve, s.resolve.current_weight, s.resolve.gamma);
}

std::string taa_report_markdown(const std::vector<TaaRow>& rows, const RunMetadata& run, const TaaReportSettings& s) {
    std::string md = "# kdop taa: ghosting and shimmer over TAA sequences\n\n";
    md += fmt::format("Each variant rectifies the history of one TAA resolve on the device ({}x{} frames; {}), as in "
                      "Ikkala et al. 2024, Sec. 4, in LDR-FLIP at {:.1f} pixels per degree (computed {}).",
                      s.width, s.height, describe_resolve(s), s.pixels_per_degree,
                      s.flip_on_device ? "on the device, kdop's flip/device_flip.h" : "on the CPU, kdop's flip/flip.h");
    // kdop's own scenes are the rows whose scene is not a sequence's.
    const bool own_scenes = std::any_of(rows.begin(), rows.end(), [&](const TaaRow& r) {
        return std::find(s.sequences.begin(), s.sequences.end(), r.scene) == s.sequences.end();
    });
    if (own_scenes)
        md += fmt::format(" kdop's own scenes are measured on two sequences each, as the paper does:\n\n"
                          "- **shimmer**: jitter on (R2, 10 entries), no animation; after {} frames, the mean FLIP "
                          "between successive frames over {} frames;\n"
                          "- **ghosting**: jitter off, animation on; after {} frames, the mean FLIP against the "
                          "aliased frame of the same instant (or its supersampled reference, where ghosting_against "
                          "says so) over {} frames;\n",
                          s.warmup, s.frames, s.warmup, s.frames);
    md += own_scenes ? "" : "\n\n";
    md += "- **ms**: the median lavapipe time of the variant's rectification pass at the frame size (not the "
          "resolve's reprojection and blend), with its quartiles Q1 and Q3 over the interleaved rounds; a variant "
          "whose median is within the larger interquartile range of its own and the fastest variant's is *within "
          "noise* of the fastest: that difference is not to be believed.\n\n";
    if (std::any_of(rows.begin(), rows.end(), [](const TaaRow& r) { return r.range == ColorRange::hdr; }))
        md += fmt::format("HDR sequences (flip = HDR-FLIP in the tables) are measured in HDR-FLIP instead, as "
                          "NVlabs/flip computes it: with the {} tone mapper, {}, each pair's error the largest "
                          "LDR-FLIP over the exposures.\n\n",
                          to_string(s.hdr.tone_mapper), describe_exposures(s.hdr));
    if (!s.sequences.empty())
        md += fmt::format("Sequences given with --sequence ({}) are measured once each, after {} frames, over all "
                          "the frames that follow: ghosting against each frame's reference where the sequence has "
                          "them (ghosting_against = reference), else against its own color; shimmer between "
                          "successive outputs, none across a camera cut.\n\n",
                          fmt::join(s.sequences | std::views::transform(markdown_text), ", "), s.warmup);
    md += fmt::format("- {} are means over the measured frames; **p95** is the 95th percentile over "
                      "the same frames (linear interpolation between order statistics, as numpy's default), which a "
                      "trail a few frames long moves where the mean hardly moves. taa_frames.csv has every frame's "
                      "figures, and taa.csv the medians too.\n",
                      measured_names(s.metrics));
    md += metric_descriptions(s.metrics);
    md += fmt::format("- taa.csv gives each mean a 95% interval (shimmer_low to shimmer_high, ghosting_low to "
                      "ghosting_high): a block bootstrap over the measured frames, in blocks of {} consecutive frames "
                      "(ceil(1 / current weight): frames of one block share their history), 2000 replicates drawn "
                      "with seed {}, the same blocks for every variant of a scene; ghosting_noise says whether a "
                      "variant's ghosting is *within noise* of the least in its scene, their paired difference's "
                      "interval holding 0. A scene or sequence of fewer than two blocks of frames has none.\n\n",
                      history_block(s.resolve.current_weight), run.seed.value_or(1));
    if (std::any_of(rows.begin(), rows.end(),
                    [](const TaaRow& r) { return std::isnan(r.mean(kShimmer)) || std::isnan(r.mean(kGhosting)); }))
        md += "A figure shown as – is not measured: one the sequence is not meant for (its sequence.json says "
              "\"measure\": [\"ghosting\"], a moving capture without jitter, whose shimmer would be the motion's, "
              "or [\"shimmer\"], a still, jittered capture, which has nothing to ghost), or shimmer where every "
              "measured frame follows a camera cut, so that no two successive outputs share a history. It is empty "
              "in the CSV and null in the JSON.\n\n";
    std::vector<std::string> scenes;
    for (const TaaRow& r : rows)
        if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
    std::vector<std::string> shown{"variant", "ms", "ms_q1", "ms_q3", "ms_noise"};
    for (const Metric& m : s.metrics)
        if (m.measured) shown.insert(shown.end(), {m.name, m.name + "_p95"});
    shown.insert(shown.end(), {"ghosting_noise", "ghosting_against", "flip"});
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        std::vector<TaaRow> in_scene;
        std::copy_if(rows.begin(), rows.end(), std::back_inserter(in_scene),
                     [&](const TaaRow& r) { return r.scene == scenes[i]; });
        // Least ghosting first, or, for a sequence meant for shimmer alone, least shimmer.
        const bool by_shimmer = std::all_of(in_scene.begin(), in_scene.end(),
                                            [](const TaaRow& r) { return std::isnan(r.mean(kGhosting)); });
        std::stable_sort(in_scene.begin(), in_scene.end(), [by_shimmer](const TaaRow& a, const TaaRow& b) {
            return by_shimmer ? a.mean(kShimmer) < b.mean(kShimmer) : a.mean(kGhosting) < b.mean(kGhosting);
        });
        md += fmt::format("## {}\n\n", markdown_text(scenes[i]));
        for (const auto& [name, content] : s.scene_contents)
            if (name == scenes[i]) md += fmt::format("The scene: {}.\n\n", markdown_text(content));
        md += fmt::format("Least {} first.\n\n{}\n", by_shimmer ? "shimmer" : "ghosting",
                          taa_table(in_scene, s.metrics).markdown(shown));
        md += worst_frames(in_scene, s.metrics);
        if (i < s.charts.size())
            md += fmt::format("What each variant costs against the ghosting and shimmer it leaves (lower left is "
                              "better): ![cost against ghosting and shimmer, {0}]({1})\n\n",
                              markdown_text(scenes[i]), markdown_destination(s.charts[i]));
        if (i < s.over_time.size())
            md += fmt::format("Each variant's figures over the measured frames: ![ghosting and shimmer over time, "
                              "{0}]({1})\n\n",
                              markdown_text(scenes[i]), markdown_destination(s.over_time[i]));
        md += paper_comparison(scenes[i], rows);
        const std::string picture = ghosting_picture_name(scenes[i]);
        const bool sequence = std::find(s.sequences.begin(), s.sequences.end(), scenes[i]) != s.sequences.end();
        if (std::find(s.pictures.begin(), s.pictures.end(), picture) != s.pictures.end())
            md += fmt::format("{}, every variant over its LDR-FLIP map against the aliased frame or the reference (the "
                              "scale under the picture); under each, the variant's ghosting (the mean over the "
                              "measured frames) and this frame's mean FLIP: ![{}]({})\n\n",
                              sequence ? "The frame where the variants' ghosting differs most (with one variant, where "
                                         "it is largest), cropped to at most 320x180 where their FLIP maps differ most"
                                       : "The ghosting sequence's frame where the objects move fastest",
                              markdown_text(scenes[i]), markdown_destination(picture));
    }
    return md + metadata_markdown(run);
}

} // namespace kdop
