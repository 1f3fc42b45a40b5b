// The evaluation every TAA figure comes from: variants x sources (kdop's scenes and frame
// sequences), each variant's resolve run over each source and measured (taa_measure.h) in LDR- or
// HDR-FLIP, on the device by default. `kdop taa` and `kdop optimize --target-ghosting` both measure
// through it, so a figure means the same wherever it is printed.
#pragma once

#include "core/result.h"
#include "flip/hdr_flip.h"
#include "generator/runnable_variant.h"
#include "generator/variant_spec.h"
#include "runtime/context.h"
#include "scenes/taa_scene.h"
#include "sequence/frame_source.h"
#include "temporal/flip_evaluator.h"
#include "temporal/own_resolve.h"
#include "temporal/resolve_options.h"
#include "temporal/taa_measure.h"
#include "temporal/taa_resolve.h"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <vector>

namespace kdop {

struct EvaluationOptions {
    ResolveOptions resolve;
    TaaSchedule schedule;     // scenes: warm-up and measured frames; sequences: the warm-up, then every frame
    double ppd = 0;           // FLIP's pixels per degree
    bool cpu_flip = false;    // FLIP on the CPU (the reference code) instead of on the device
    ExposureOptions exposure; // HDR-FLIP's, for HDR sequences
    Metrics metrics = default_metrics(); // what each frame is measured with (temporal/metrics.h)
    // Where a source upscales, one more row after the variants': the spatial-only upscale of the
    // same input (build_spatial_upscale_shader), so a reader sees what the history buys.
    bool spatial_upscale = false;
    // A renderer's own resolve, run in place of kdop's (kdop taa --resolve). The options of kdop's
    // resolve that its shader has no counterpart of do not apply: the values its map's roles take
    // (the current weight, gamma, the sample distance) do, and there is no spatial-only row.
    std::optional<OwnResolve> own_resolve;
};

// One variant's figures on one scene or sequence.
struct EvaluationRow {
    std::size_t variant = 0;   // into the evaluation's specs; specs().size() for the spatial-only upscale
    std::string source;        // the scene's or sequence's name
    std::vector<double> means; // by metric (MetricId); NaN where not measured (the source's roles)
    double mean(std::size_t metric) const { return metric < means.size() ? means[metric] : NAN; }
    bool against_reference = false;      // ghosting against reference frames, not each frame's own color
    ColorRange range = ColorRange::ldr;  // measured in LDR-FLIP or HDR-FLIP
    std::shared_ptr<const Image> trail;  // scenes: the ghosting sequence's frame scene.trail_frame(schedule)
    std::vector<std::string> notes;      // HDR-FLIP's exposure notes (ExposureRange::note), once each
    std::vector<FrameFigures> per_frame; // each measured frame's figures; shimmer and ghosting are their means
    double upscale = 1;                  // the source's output width over its input width
};

struct EvaluationObserver {
    // Each measured output: `sequence` (a scene's are <scene>-shimmer and <scene>-ghosting), the
    // variant, the frame's index. An error stops the evaluation.
    std::function<Result<void>(const std::string& sequence, std::size_t variant, std::size_t index,
                               const Image& output)>
        output;
    // After each frame of a source, every variant resolved and measured on it, naming the source
    // (a scene's name for both of its sequences). An error stops the evaluation.
    std::function<Result<void>(const std::string& source)> frame;
    // After each measured frame, every variant's figures and output on it (a scene's sequences are
    // <scene>-shimmer and <scene>-ghosting), and with `maps` their FLIP maps (MeasuredFrame::maps).
    MeasuredFrameObserver measured;
    bool maps = false;
    // What frame() names, where not the frame source's own name (set by measure() for a scene).
    std::string source;
};

class TaaEvaluation {
public:
    // The resolve around every spec, built in-process. `context` must outlive the evaluation.
    static Result<TaaEvaluation> create(const Context& context, std::vector<VariantSpec> specs,
                                        const EvaluationOptions& options);

    const std::vector<VariantSpec>& specs() const { return specs_; }
    // What each frame is measured with: EvaluationRow::means and FrameFigures index it.
    const Metrics& metrics() const { return options_.metrics; }

    // Other variants on the same device, its FLIP evaluators kept: kdop optimize measures one
    // fitted set after another.
    Result<void> set_variants(std::vector<VariantSpec> specs);

    // Every variant on `scene` (both of its sequences), or on `sequence`, in spec order: one pass
    // over the frames, each drawn or read once and resolved by every variant against its own history.
    Result<std::vector<EvaluationRow>> measure(const TaaScene& scene, const EvaluationObserver& observer = {});
    Result<std::vector<EvaluationRow>> measure(const SequenceFrames& sequence, const EvaluationObserver& observer = {});

    // The rows measure() gives for `source`: one per variant, and the spatial-only upscale's where
    // it upscales and the options ask for it (EvaluationRow::variant).
    std::size_t shader_count(const FrameSource& source) const;

    // The frames measure() goes through for `scene` (observer.frame's calls); a sequence's are its
    // frame_count().
    std::size_t frames(const TaaScene& scene) const;

    // The FLIP the figures of outputs of one size are measured with (the device's, one evaluator per
    // size made when first needed, or with --cpu-flip the CPU's): what the pictures show too. Valid
    // while the evaluation lives.
    Result<FlipEvaluator*> flip_evaluator(std::uint32_t width, std::uint32_t height);

    // Every variant on one frame source: the one path the measure()s above take, and an NSS
    // capture's. `nearer_larger`: the source's depth convention (only --dilate-motion reads depth).
    Result<std::vector<EvaluationRow>> measure(const FrameSource& source, bool nearer_larger,
                                               const EvaluationObserver& observer);

private:
    TaaEvaluation(const Context& context, const EvaluationOptions& options);
    // The resolve of variant `v` for a depth convention (only --dilate-motion reads depth), and
    // for upscaling or not; a renderer's own resolve (options.own_resolve) is the same for all,
    // with the roles it is bound by.
    Result<const BoundOwnResolve*> shader(std::size_t v, bool nearer_larger, bool upscale = false);
    // One resolve of every variant's shader, for `source`'s frame sizes and a depth convention;
    // where it upscales and options.spatial_upscale asks, the spatial-only upscale last.
    Result<TaaResolve*> resolve(const FrameSource& source, bool nearer_larger);

    const Context* context_;
    std::vector<VariantSpec> specs_;
    EvaluationOptions options_;
    // By upscaling and depth convention (2 x upscale + nearer_larger), built when first needed;
    // the roles only for a renderer's own resolve, built once, in the first.
    std::vector<BoundOwnResolve> shaders_[4];
    std::unique_ptr<RunnableVariant> spatial_; // the spatial-only upscale, built when first needed
    // Input width and height, output width and height, nearer_larger.
    using ResolveKey = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t, bool>;
    std::unique_ptr<TaaResolve> resolve_; // the last resolve(), for its key
    ResolveKey resolve_key_;
    std::unique_ptr<HdrFlip> cpu_flip_;
    // By frame size: the device's FLIP, and the evaluator over it (or over cpu_flip_).
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::unique_ptr<DeviceFlip>> device_flips_;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::unique_ptr<FlipEvaluator>> evaluators_;
};

} // namespace kdop
