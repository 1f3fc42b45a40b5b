// What `kdop taa` writes: taa.csv (and .json), one row per variant and scene; taa_frames.csv (and
// .json), one row per measured frame and variant; and report.md, which
// shows each scene's rows and, for the paper's two scenes, kdop's figures beside Tables 1 and 2 of
// Ikkala et al. 2024 with each method's rank, so the orderings can be compared at a glance.
#pragma once

#include "core/variant_key.h"
#include "flip/hdr_flip.h"
#include "harness/block_bootstrap.h"
#include "harness/run_metadata.h"
#include "harness/table.h"
#include "sequence/sequence.h"
#include "temporal/metrics.h"
#include "temporal/resolve_options.h"

#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace kdop {

// One metric's figures in a row of taa.csv: its MetricSummary over the measured frames, its 95%
// block-bootstrap interval (taa_intervals.h; unknown where the frames are too few) and its worst
// frame as "<sequence> frame <index>" (empty where none is measured).
struct MetricFigures {
    double mean = NAN, median = NAN, p95 = NAN;
    Interval interval;
    std::string worst_frame;
};

struct TaaRow {
    VariantKey key; // a clip variant, or the spatial-only upscale (a Mode::shader of its own, no time)
    std::string scene;
    double upscale = 1; // the scene's output width over its input width: 1 where it does not upscale
    // The lavapipe time of the variant's rectification pass at the frame size: median and quartiles.
    double ms = NAN, ms_q1 = NAN, ms_q3 = NAN;
    // Each metric's figures, by MetricId (temporal/metrics.h); NaN where the scene or sequence is
    // not meant for one (sequence.json's "measure") or the run does not measure it.
    std::vector<MetricFigures> figures;
    double mean(std::size_t metric) const { return metric < figures.size() ? figures[metric].mean : NAN; }
    // The truth the metrics that compare with one were measured against: "aliased" (each frame's
    // own color, the paper's ground truth with jitter off) or "reference" (the sequence's
    // reference frames).
    std::string truth = "aliased";
    // What the FLIP metrics were measured in: LDR-FLIP, or HDR-FLIP for an HDR sequence.
    ColorRange range = ColorRange::ldr;
    // Whether the ranking metric's mean (ghosting's, ranking_first) is within noise of the least in
    // the scene (taa_intervals.h); unknown where the frames are too few.
    std::optional<bool> within_noise;
};

// Whether `row`'s time differs from the fastest row's by no more than the larger interquartile
// range of the two: a difference a reader should not believe.
bool within_noise_of_fastest(const TaaRow& row, const std::vector<TaaRow>& rows);

// taa.csv: per measured metric of `metrics` its mean, median, p95 and interval, then the worst frames.
Table taa_table(const std::vector<TaaRow>& rows, const Metrics& metrics);

// One measured frame of one variant: the figures the means of taa.csv are the means of.
struct TaaFrameRow {
    VariantKey key;
    std::string scene;    // the row of taa.csv it belongs to
    std::string sequence; // the frames it was measured on: the sequence, or a scene's -shimmer or -ghosting one
    std::size_t frame = 0;
    std::vector<double> values;         // by MetricId; NaN: not measured on this frame
    ColorRange range = ColorRange::ldr; // measured in LDR-FLIP or HDR-FLIP (not a column: taa.csv has it)
    double value(std::size_t metric) const { return metric < values.size() ? values[metric] : NAN; }
};

Table taa_frames_table(const std::vector<TaaFrameRow>& rows, const Metrics& metrics);

struct TaaReportSettings {
    std::uint32_t width = 0, height = 0, warmup = 0, frames = 0;
    double pixels_per_degree = 0;
    std::vector<std::string> pictures;  // per scene, relative to the report
    std::vector<std::string> charts;    // per scene, cost against ghosting and shimmer; empty: none drawn
    std::vector<std::string> over_time; // per scene, each variant's figures over the frames; empty: none drawn
    ResolveOptions resolve;
    std::string own_resolve; // a renderer's resolve measured instead of kdop's (OwnResolve::label); empty: kdop's
    // kdop's own scenes measured: name and what the scene is made of (TaaScene::content).
    std::vector<std::pair<std::string, std::string>> scene_contents;
    // The sequences measured (`kdop taa --sequence`), by name, beside kdop's own scenes.
    std::vector<std::string> sequences;
    bool flip_on_device = false;         // ghosting and shimmer measured by the device's FLIP, not the CPU's
    ExposureOptions hdr;                 // HDR-FLIP's tone mapper and exposures, for the HDR sequences
    Metrics metrics = default_metrics(); // what the rows were measured with
};

// The resolve as the reports describe it: kdop's with its options, or a renderer's by name.
std::string describe_resolve(const TaaReportSettings& settings);

std::string taa_report_markdown(const std::vector<TaaRow>& rows, const RunMetadata& run,
                                const TaaReportSettings& settings);

} // namespace kdop
