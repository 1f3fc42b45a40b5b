// The metrics (temporal/metrics.h) of one TAA resolve over one frame source, after `warmup` frames
// so the history is full; by default shimmer and ghosting as Ikkala et al. 2024 measure them (Sec.
// 4), in LDR-FLIP (flip/flip.h), or in HDR-FLIP (flip/hdr_flip.h) where the source's frames are HDR
// (FrameSource::color_range):
//   ghosting: the mean FLIP between each output and its frame's reference, or, where the source has
//             none, the frame's own color: the aliased frame a renderer without TAA shows, which
//             is the paper's ground truth for jitter-off sequences (with jitter off the resolve no
//             longer antialiases, so what differs is the ghosting).
//   shimmer:  the mean FLIP between successive outputs (none across a camera cut). On a still,
//             jittered sequence only the resolve's rejection of valid history makes successive
//             outputs differ, so this is the temporal instability clipping causes.
// kdop's own scenes are measured as the paper does: shimmer on a still, jittered sequence and
// ghosting on a moving one without jitter (measure_scene below); a captured sequence gives both.
// One loop serves every source and every FLIP: the frames it compares are handles into the FLIP
// evaluator's store (temporal/output_store.h), on the host or on the device.
#pragma once

#include "core/result.h"
#include "flip/hdr_flip.h"
#include "images/image.h"
#include "scenes/taa_scene.h"
#include "sequence/frame_source.h"
#include "temporal/flip_evaluator.h"
#include "temporal/metrics.h"
#include "temporal/taa_resolve.h"
#include "temporal/trail_picture.h"

#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace kdop {

struct SequenceMeasurement {
    // Each metric's mean over the measured frames (MetricSummary::mean), by MetricId; NaN for one
    // the source is not meant for or the run does not measure.
    std::vector<double> means;
    double mean(std::size_t metric) const { return metric < means.size() ? means[metric] : NAN; }
    ColorRange range = ColorRange::ldr;  // the source's: measured in LDR-FLIP or in HDR-FLIP
    bool against_reference = false;      // ghosting against the frames' references, not their own color
    std::size_t frames = 0;              // frames measured
    std::vector<FrameFigures> per_frame; // each measured frame's, in order: the means are their means
    // Each FlipFigure::note met, once, with the first frame it was met at and how many more: what a
    // user is warned of ("color/0042.exr and 3 more frames: the reference is black: ...").
    std::vector<std::string> notes;
};

// Whether `context` can resolve and measure frames of width x height with `variants` variants in
// one pass: the resolve's images within its limits and, with `device_flip`, FLIP's
// (DeviceFlip::check_limits), and both in memory (each variant holds its history and its previous
// output). What a
// command checks for every size it will measure before any work, so a size that cannot be measured
// is refused in a second, not after minutes; the error says what to do instead.
Result<void> check_measurable(const Context& context, std::uint32_t width, std::uint32_t height, bool device_flip,
                              std::size_t variants = 1);

// read_sequence, and what the resolve needs of it checked before any frame is read: more frames
// than `warmup` (a usage error: the command line's --warmup), and with --dilate-motion depth on
// every frame that has a history. Errors name the folder (and frame) and `option`, the one that
// gave the folder (--sequence, kdop choose's --fit or --validate).
Result<Sequence> read_resolvable_sequence(const std::filesystem::path& dir, std::uint32_t warmup,
                                          const ResolveOptions& options, std::string_view option = "--sequence");

// Called with each measured frame's index and output; an error stops the measurement.
using OutputObserver = std::function<Result<void>(std::size_t index, const Image& output)>;
// The same for a resolve of several shaders, with the shader's index.
using ShaderOutputObserver = std::function<Result<void>(std::size_t shader, std::size_t index, const Image& output)>;

// Called after each frame, measured or not; an error stops the measurement (another rank's failure,
// harness/ranks.h).
using FrameObserver = std::function<Result<void>()>;

// Resolves every frame of `source` on `resolve` (a resolve of one shader: with more, every shader
// runs and the first one's figures come back), measuring after `warmup` the figures the source is
// meant for (FrameSource::roles; each costs one FLIP per measured frame). Frames and references
// must keep to the source's range ([0, 1] for ldr, not negative for hdr): a value outside is
// refused, naming the frame, the pixel and the value, never clamped. `on_frame` is called after
// each frame, measured or not.
Result<SequenceMeasurement> measure_sequence(TaaResolve& resolve, const FrameSource& source, std::uint32_t warmup,
                                             FlipEvaluator& flip, const OutputObserver& on_output = {},
                                             const FrameObserver& on_frame = {},
                                             const Metrics& metrics = default_metrics());

struct TaaMeasurement {
    std::vector<double> means; // shimmer's of the shimmer sequence, the others' of the ghosting sequence
    double mean(std::size_t metric) const { return metric < means.size() ? means[metric] : NAN; }
    bool against_reference = false; // ghosting against the frames' references (3-D scenes with --reference-samples)
    // The ghosting sequence's frame scene.trail_frame(schedule): where a trail is longest.
    Image trail;
    // The shimmer sequence's measured frames, then the ghosting sequence's.
    std::vector<FrameFigures> per_frame;
};

// Called with the sequence's name (shimmer_frames' or ghosting_frames', scenes/taa_scene.h), a measured
// frame's index and its output.
using SceneOutputObserver =
    std::function<Result<void>(const std::string& sequence, std::size_t index, const Image& output)>;

// Called with the sequence's name, the shader's index, the frame's index and its output.
using SceneShaderOutputObserver = std::function<Result<void>(const std::string& sequence, std::size_t shader,
                                                             std::size_t index, const Image& output)>;

// The figure a frame's FLIP map shows (MeasuredFrame::maps, report.html's viewer): ghosting where the
// source measures it, else shimmer.
inline bool maps_show_ghosting(SequenceRoles roles) { return roles.ghosting; }

// One measured frame, every shader done, as an observer sees it (all valid during the call): what
// keeps the frames a picture or the report's viewer shows.
struct MeasuredFrame {
    std::string_view sequence; // the source's name
    std::size_t index = 0;
    std::span<const FrameFigures> figures; // each shader's, in order
    // Where maps were asked for: each shader's FLIP map of the figure maps_show_ghosting names, the
    // one its figure is the mean of (empty for shimmer after a camera cut). Else empty.
    std::span<const std::vector<float>> maps;
    // Each shader's output on the frame (within range), brought to the host on the first call: an
    // output kept on the device costs a read-back (and its memory until the call returns), so an
    // observer asks for the frames it keeps alone, deciding by their figures.
    std::function<Result<std::vector<const Image*>>()> outputs;
    // What ghosting is measured against: the reference, else the color (on the host).
    const Image* truth = nullptr;
};
// Called after each measured frame; an error stops the measurement.
using MeasuredFrameObserver = std::function<Result<void>(const MeasuredFrame& frame)>;

// Every shader of `resolve` over `source` in one pass: each frame drawn or read and checked once,
// then resolved and measured by every shader against its own history. Each shader's figures are
// those measure_sequence gives it alone (the sums in the same order). `on_frame` is called after
// each frame, all shaders done; `on_measured` after each measured one, before `on_frame`, with
// the frame's FLIP maps where `maps` asks for them (each is a read-back: only for an observer that
// shows them).
Result<std::vector<SequenceMeasurement>>
measure_sequence_all(TaaResolve& resolve, const FrameSource& source, std::uint32_t warmup, FlipEvaluator& flip,
                     const ShaderOutputObserver& on_output = {}, const FrameObserver& on_frame = {},
                     const MeasuredFrameObserver& on_measured = {}, bool maps = false,
                     const Metrics& metrics = default_metrics());
// A scene's figures from its two sequences' means (by metric): each metric's from the sequence
// that measures it, the still one (shimmer's role) or the moving one (ghosting's).
std::vector<double> scene_means(std::span<const double> still, std::span<const double> moving);

// Both of a scene's sequences through every shader of `resolve`, in one pass each.
Result<std::vector<TaaMeasurement>> measure_scene_all(TaaResolve& resolve, const TaaScene& scene,
                                                      const TaaSchedule& schedule, FlipEvaluator& flip,
                                                      const SceneShaderOutputObserver& on_output = {},
                                                      const FrameObserver& on_frame = {},
                                                      const MeasuredFrameObserver& on_measured = {}, bool maps = false,
                                                      const Metrics& metrics = default_metrics());

// Both of a scene's sequences on `resolve`.
Result<TaaMeasurement> measure_scene(TaaResolve& resolve, const TaaScene& scene, const TaaSchedule& schedule,
                                     FlipEvaluator& flip, const SceneOutputObserver& on_output = {},
                                     const FrameObserver& on_frame = {}, const Metrics& metrics = default_metrics());

// A resolve's output ready for FLIP (and, for ldr, PNG): the resolve's blends and clips land on
// segments between colors in the range, so anything beyond it is float rounding. Values outside
// by no more than 1e-4 (for hdr, 1e-4 times the pixel's largest channel, when that is above 1)
// are moved onto the range; anything further, or not finite (a bug, not rounding), is an error
// naming the pixel. The frame is checked and moved onto the range in place.
Result<Image> within_range(Image frame, ColorRange range, std::string_view what);
// How far outside the range within_range lets a value lie (times the scale it says).
constexpr float kOutputRounding = 1e-4f;
// within_range's error for pixel (x, y) of `what`, where it holds a value outside; nullopt where it
// holds none.
std::optional<std::string> outside_range(glm::vec4 pixel, ColorRange range, std::string_view what, std::uint32_t x,
                                         std::uint32_t y);

} // namespace kdop
