// The temporal metrics a resolve's outputs are measured with, as one table: each row a metric's
// name, unit, what it compares and how it is computed. Every figure kdop taa writes (taa.csv and
// its JSON, taa_frames.csv, report.md, report.html, the over-time charts) is made from this table,
// so a new metric is one row and one computation (docs/development.md, "A new metric").
//
//   shimmer   FLIP between successive outputs (Ikkala et al. 2024, Sec. 4)
//   ghosting  FLIP between each output and its frame's truth: the reference, else the frame's color
//   psnr      PSNR of each output against the frame's reference
//   tpsnr     PSNR of each output's change from the output before against the reference's change
//             from the reference before (temporal PSNR, as Arm's NSS evaluation measures it)
//
// FLIP metrics are LDR-FLIP on LDR sources and HDR-FLIP on HDR ones. PSNR and tPSNR take values as
// the pictures show them (LDR as they are, HDR tone mapped at exposure 0 with HDR-FLIP's tone
// mapper), with a peak of 1; identical frames give +inf, written as such ("inf", "∞"), not a large
// number. A metric is measured only where the source is meant for its role (sequence.json's
// "measure"), and one that needs a reference only on sources that have one: elsewhere it is
// absent, never 0.
#pragma once

#include "core/result.h"
#include "sequence/sequence.h"
#include "temporal/flip_evaluator.h"
#include "temporal/output_store.h"

#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

// What a metric compares.
enum class Compared {
    truth,    // each output against its frame's truth
    previous, // each output against the output before
    change,   // each output's change from the one before against the truth's change
};

// Which of a source's roles (SequenceRoles) a metric is measured under.
enum class MetricRole { ghosting, shimmer };

// What a metric's computation gets, for one shader on one measured frame: frames held in the
// evaluator's store (previous_*: none on a frame that starts a history or follows an unmeasured one).
struct MetricFrame {
    FlipEvaluator& flip;
    ColorRange range;
    FrameHandle truth, previous_truth, output, previous_output;
    bool map = false; // the per-pixel map wanted (FLIP metrics: what the viewer shows)
};

struct Metric {
    std::string name;        // its columns': <name>, <name>_median, <name>_p95, ... in taa.csv
    std::string unit;        // "FLIP", "dB"
    std::string description; // what it compares, as report.md and report.html say it
    Compared compares = Compared::truth;
    MetricRole role = MetricRole::ghosting;
    bool flip = false;             // LDR-FLIP, or HDR-FLIP on HDR sources
    bool needs_reference = false;  // measured only against reference frames
    bool higher_is_better = false; // its worst frame is its least
    bool measured = true;          // measured by this run (--metrics)
    int digits = 4;                // decimals shown in Markdown and HTML
    std::function<Result<FlipFigure>(const MetricFrame&)> compute;
};

// A registry of metrics: kdop's own, indexed by MetricId, and any a caller adds after them.
using Metrics = std::vector<Metric>;
enum MetricId : std::size_t { kShimmer, kGhosting, kPsnr, kTpsnr, kBuiltinMetrics };

// kdop's metrics, shimmer and ghosting measured (the paper's), PSNR and tPSNR not.
Metrics default_metrics();
// The same with exactly the metrics `names` names measured (kdop taa's --metrics); an unknown
// name is a usage error naming it and the known ones, as is a list without ghosting.
Result<Metrics> metrics_named(std::span<const std::string> names);
// "shimmer, ghosting, psnr, tpsnr".
std::string metric_names(const Metrics& metrics);

// The metrics' indices with ghosting, what kdop ranks variants by, first, then the others in the
// registry's order: the order of taa_frames.csv's figures and taa.csv's worst frames.
std::vector<std::size_t> ranking_first(const Metrics& metrics);

// Whether `metric` is measured on a source with `roles` (and `has_reference`).
bool measured_on(const Metric& metric, SequenceRoles roles, bool has_reference);

// One measured frame's figures, indexed by the registry (MetricId): NaN where the frame has none
// (shimmer on a frame that starts a history, a metric not measured or not meant for the source).
struct FrameFigures {
    std::string sequence; // the source's name
    std::size_t index = 0;
    std::vector<double> values;
    double value(std::size_t metric) const { return metric < values.size() ? values[metric] : NAN; }
};

// The figures of one metric over a sequence's measured frames: the mean over the frames that have
// one (NaN for none; +inf where one is), its median and 95th percentile (linear interpolation
// between order statistics, numpy's default), and its worst frame (the largest, or the least for a
// metric where higher is better; the earliest of equals), an index into the frames.
struct MetricSummary {
    double mean = NAN, median = NAN, p95 = NAN;
    std::optional<std::size_t> worst;
};
MetricSummary summarize(std::span<const FrameFigures> frames, std::size_t metric, bool higher_is_better = false);

// PSNR of `test` against `reference` over R, G and B with a peak of 1: 10 log10(1 / MSE), +inf
// for identical images. Both of one size.
double psnr(const Image& reference, const Image& test);
// tPSNR: the same of (test - test_before) against (reference - reference_before).
double temporal_psnr(const Image& reference_before, const Image& reference, const Image& test_before,
                     const Image& test);

} // namespace kdop
