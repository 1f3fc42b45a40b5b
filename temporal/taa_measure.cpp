#include "temporal/taa_measure.h"

#include "core/interrupt.h"
#include "core/memory_budget.h"
#include "core/parallel_for.h"
#include "harness/statistics.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <span>

namespace kdop {

std::optional<std::string> outside_range(glm::vec4 pixel, ColorRange range, std::string_view what, std::uint32_t x,
                                         std::uint32_t y) {
    const bool hdr = range == ColorRange::hdr;
    // Rounding scales with the colors the resolve blended: for HDR, the pixel's largest.
    const float scale = hdr ? std::max({1.0f, pixel.r, pixel.g, pixel.b}) : 1.0f;
    for (int c = 0; c < 3; ++c) {
        const float v = pixel[c];
        const bool within =
            v >= -kOutputRounding * scale && (hdr ? std::isfinite(scale) : v <= 1 + kOutputRounding); // NaN fails
        if (!within)
            return fmt::format("{}: pixel ({}, {}) has {} {}, outside {} by more than rounding", what, x, y, "RGB"[c],
                               v, hdr ? "[0, inf)" : "[0, 1]");
    }
    return std::nullopt;
}

Result<Image> within_range(Image frame, ColorRange range, std::string_view what) {
    const bool hdr = range == ColorRange::hdr;
    for (std::uint32_t y = 0; y < frame.height; ++y)
        for (std::uint32_t x = 0; x < frame.width; ++x) {
            glm::vec4& pixel = frame.at(x, y);
            if (auto outside = outside_range(pixel, range, what, x, y)) return fail(std::move(*outside));
            for (int c = 0; c < 3; ++c) pixel[c] = hdr ? std::max(pixel[c], 0.0f) : std::clamp(pixel[c], 0.0f, 1.0f);
        }
    return frame;
}

Result<void> check_measurable(const Context& context, std::uint32_t width, std::uint32_t height, bool device_flip,
                              std::size_t variants) {
    const std::uint32_t limit = context.properties().limits.maxImageDimension2D;
    if (width > limit || height > limit)
        return fail(fmt::format("{}x{} frames are larger than {} allows: at most {} pixels on a side", width, height,
                                context.device_name(), limit));
    if (device_flip)
        if (auto ok = DeviceFlip::check_limits(context, width, height); !ok)
            return fail(ok.error().message + "; --cpu-flip measures with the CPU's FLIP, which has no such limit");
    // The resolve's pass and its four inputs, three frames' images (color, motion, depth, reference:
    // the one resolved and two read ahead), and per variant its history (the last output), its
    // checked copy, its previous output and its output at a sequence's pictured frame; on lavapipe
    // device memory is this process's memory.
    const std::uint64_t resolve =
        rectify_pass_bytes(width, height) + (12 + 4 * std::uint64_t(variants)) * image_bytes(width, height);
    const std::uint64_t flip = device_flip ? DeviceFlip::bytes(width, height) : ldr_flip_bytes(width, height);
    return check_memory(fmt::format("measuring {}x{} frames", width, height), resolve + flip);
}

Result<Sequence> read_resolvable_sequence(const std::filesystem::path& dir, std::uint32_t warmup,
                                          const ResolveOptions& options, std::string_view option) {
    auto sequence = read_sequence(dir);
    if (!sequence) return sequence;
    if (warmup >= sequence->frames.size())
        // The suggestion keeps two thirds of the frames to measure: enough history before them for
        // the default blend (current weight 0.1 leaves 0.9^16, under a fifth, of the first frame
        // after the 16 frames the Blender example's 48 allow).
        return usage_fail(fmt::format("{}: {}: {} frames, and --warmup {} leaves none to measure; give a shorter "
                                      "warm-up, e.g. --warmup {} (a third of the frames)",
                                      option, dir.string(), sequence->frames.size(), warmup,
                                      std::max<std::size_t>(1, sequence->frames.size() / 3)));
    if (options.dilate_motion)
        for (std::size_t i = 0; i < sequence->frames.size(); ++i)
            if (!sequence->starts_history(i) && sequence->frames[i].depth.empty())
                return fail(fmt::format("--dilate-motion takes the motion of the nearest neighbor by depth, and "
                                        "frames[{}] of {} has no \"depth\" file",
                                        i, (sequence->dir / "sequence.json").string()));
    return sequence;
}

namespace {

// Refuses a color outside the range the source keeps to, naming where it is.
Result<void> check_range(const Image& image, ColorRange range, const std::string& label, std::string_view what) {
    const bool hdr = range == ColorRange::hdr;
    for (std::uint32_t y = 0; y < image.height; ++y)
        for (std::uint32_t x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float v = image.at(x, y)[c];
                if (hdr && !(v >= 0.0f && std::isfinite(v)))
                    return fail(fmt::format("{}: {} pixel ({}, {}) has {} {}; HDR-FLIP takes finite linear values "
                                            "from 0 up (kdop does not clamp them)",
                                            label, what, x, y, "RGB"[c], v));
                if (!hdr && !(v >= 0.0f && v <= 1.0f))
                    return fail(fmt::format("{}: {} pixel ({}, {}) has {} {}, outside [0, 1]; this sequence is "
                                            "measured in LDR-FLIP, which takes linear values from 0 to 1: an HDR "
                                            "sequence says so in its sequence.json, \"color\": {{\"range\": "
                                            "\"hdr\"}}, and is measured in HDR-FLIP (kdop does not clamp it)",
                                            label, what, x, y, "RGB"[c], v));
            }
    return {};
}

} // namespace

namespace {

// One shader's measurement as the frames go by: each metric's figures and the notes met. Its frames
// are handles into the evaluator's store (temporal/output_store.h), wherever that keeps them.
class Meter {
public:
    Meter(const FrameSource& source, const Metrics& metrics) : metrics_(&metrics) {
        m_.against_reference = source.has_reference();
        m_.range = source.color_range();
        sequence_ = source.name();
        for (const Metric& metric : metrics) {
            measured_.push_back(measured_on(metric, source.roles(), source.has_reference()));
            // A metric the run asked for that this source cannot give: said, not left to a blank.
            if (!measured_.back() && measured_on(metric, source.roles(), true))
                m_.notes.push_back(fmt::format("{} not measured: {} has no reference frames to compare with",
                                               metric.name, source.name()));
        }
        // The map the viewer shows: ghosting where the source measures it, else shimmer.
        mapped_ = maps_show_ghosting(source.roles()) ? kGhosting : kShimmer;
    }

    // Frame `i` is measured: measure() gives its figures, in any order.
    void begin(std::size_t i) {
        m_.per_frame.push_back(FrameFigures{sequence_, i, std::vector<double>(metrics_->size(), NAN)});
        ++m_.frames;
        map_.clear();
    }
    // Metric `metric` of the frame, where it is measured and the frame has what it compares; with
    // `frame.map`, the map of the metric the viewer shows is kept (take_map()).
    Result<void> measure(std::size_t metric, MetricFrame frame, const std::string& label) {
        const Metric& m = (*metrics_)[metric];
        if (!measured_[metric]) return {};
        if (m.compares != Compared::truth && !frame.previous_output) return {};
        if (m.compares == Compared::change && !frame.previous_truth) return {};
        frame.map = frame.map && metric == mapped_;
        auto figure = m.compute(frame);
        if (!figure) return fail(fmt::format("{}: {} ({}): {}", label, m.name, m.description, figure.error().message));
        if (!figure->note.empty()) {
            auto [it, first] = notes_.try_emplace(figure->note, Met{label, 0});
            if (!first) ++it->second.more;
        }
        if (frame.map) map_ = std::move(figure->map);
        m_.per_frame.back().values[metric] = figure->mean;
        return {};
    }
    const FrameFigures& last_figures() const { return m_.per_frame.back(); }
    // The map kept by the last measure() (empty where none was asked for or measured).
    std::vector<float> take_map() { return std::move(map_); }

    SequenceMeasurement finish() {
        for (const auto& [note, met] : notes_)
            m_.notes.push_back(met.more ? fmt::format("{} and {} more frame{}: {}", met.first_label, met.more,
                                                      met.more == 1 ? "" : "s", note)
                                        : fmt::format("{}: {}", met.first_label, note));
        for (std::size_t metric = 0; metric < metrics_->size(); ++metric) {
            const Metric& m = (*metrics_)[metric];
            const double mean = summarize(m_.per_frame, metric, m.higher_is_better).mean;
            m_.means.push_back(measured_[metric] ? mean : NAN);
            // A figure of successive outputs where every measured frame starts a new history (a
            // camera cut on each) has no pair: absent, not 0.
            if (measured_[metric] && std::isnan(mean) && m.compares != Compared::truth)
                m_.notes.push_back(fmt::format("{} not measured: every measured frame starts a new history (a "
                                               "camera cut), so no two successive outputs share one",
                                               m.name));
        }
        return std::move(m_);
    }

private:
    struct Met {
        std::string first_label;
        std::size_t more = 0;
    };
    const Metrics* metrics_;
    std::vector<bool> measured_; // by metric: on this source
    std::size_t mapped_;
    std::string sequence_;
    SequenceMeasurement m_;
    std::vector<float> map_;
    std::map<std::string, Met> notes_; // by note
};

// Each frame of a source resolved by every shader: read (a frame ahead, on a worker, while the
// device works) or drawn on the device, and checked once where it reaches the host, whatever the
// number of shaders.
class FrameReader {
public:
    FrameReader(TaaResolve& resolve, const FrameSource& source, std::uint32_t warmup)
        : resolve_(resolve), source_(source), warmup_(warmup) {
        if (source.reads_ahead())
            ahead_.emplace(source.frame_count(), 1, [&source](std::size_t i) { return source.frame(i); });
        // A source that draws on the device draws every frame straight into the resolve: motion and
        // depth never come back, color and reference only for the frames measured.
        // Not where the resolve converts the motion on the host (a renderer's own convention).
        on_device_ = ahead_ || !resolve.takes_device_frames() ? nullptr : source.device_frames();
    }

    // Frame `i` through every shader, its outputs read back with `read_outputs`; the frame as it
    // reached the host (nullopt for a frame drawn on the device before the warm-up's end).
    Result<std::optional<LoadedFrame>> resolve(std::size_t i, bool read_outputs, const std::string& label) {
        const bool starts = source_.starts_history(i), measured = i >= warmup_;
        if (on_device_) {
            auto drawn = resolve_.advance_all(*on_device_, i, starts, read_outputs, measured);
            if (!drawn) return fail(fmt::format("{}: {}", label, drawn.error().message));
            if (!measured) return std::nullopt;
            if (auto ok = check(*drawn, i, label); !ok) return std::unexpected(ok.error());
            return std::move(*drawn);
        }
        auto read = ahead_ ? ahead_->take() : source_.frame(i);
        if (!read) return std::unexpected(read.error());
        if (auto ok = check(*read, i, label); !ok) return std::unexpected(ok.error());
        if (auto ok = resolve_.advance_all(*read, starts, read_outputs, std::uint32_t(i)); !ok)
            return fail(fmt::format("{}: {}", label, ok.error().message));
        return std::move(*read);
    }

private:
    Result<void> check(const LoadedFrame& frame, std::size_t i, const std::string& label) const {
        const ColorRange range = source_.color_range();
        const bool against_reference = source_.has_reference();
        if (auto ok = check_range(frame.color, range, label, "color"); !ok) return ok;
        if (frame.reference.has_value() != against_reference)
            return fail(fmt::format("{}: {} a reference, unlike the sequence's others; give every frame a "
                                    "reference or none",
                                    label, against_reference ? "has no" : "has"));
        if (i >= warmup_ && against_reference) return check_range(*frame.reference, range, label, "reference");
        return {};
    }

    TaaResolve& resolve_;
    const FrameSource& source_;
    std::uint32_t warmup_;
    std::optional<Prefetch<Result<LoadedFrame>>> ahead_;
    const DeviceFrames* on_device_ = nullptr;
};

// A measured frame, every shader done, as `on_measured` sees it. The outputs it brought to the host
// are let go when it returns: the store keeps them where they were measured.
Result<void> observe(OutputStore& store, std::vector<Meter>& meters, std::span<const FrameHandle> outputs,
                     FrameHandle truth, std::string_view sequence, std::size_t index, bool maps,
                     const MeasuredFrameObserver& on_measured) {
    std::vector<FrameFigures> figures;
    std::vector<std::vector<float>> frame_maps;
    for (std::size_t s = 0; s < meters.size(); ++s) {
        figures.push_back(meters[s].last_figures());
        if (maps) frame_maps.push_back(meters[s].take_map());
    }
    auto shown_truth = store.image(truth);
    if (!shown_truth) return std::unexpected(shown_truth.error());
    auto shown_outputs = [&]() -> Result<std::vector<const Image*>> {
        std::vector<const Image*> images;
        for (const FrameHandle output : outputs) {
            auto image = store.image(output);
            if (!image) return std::unexpected(image.error());
            images.push_back(*image);
        }
        return images;
    };
    auto observed = on_measured(MeasuredFrame{.sequence = sequence,
                                              .index = index,
                                              .figures = figures,
                                              .maps = frame_maps,
                                              .outputs = shown_outputs,
                                              .truth = *shown_truth});
    for (const FrameHandle output : outputs) store.let_go(output);
    return observed;
}

} // namespace

Result<std::vector<SequenceMeasurement>>
measure_sequence_all(TaaResolve& resolve, const FrameSource& source, std::uint32_t warmup, FlipEvaluator& flip,
                     const ShaderOutputObserver& on_output, const FrameObserver& on_frame,
                     const MeasuredFrameObserver& on_measured, bool maps, const Metrics& metrics) {
    const std::size_t count = source.frame_count();
    if (warmup >= count)
        return fail(
            fmt::format("{}: {} frames, and a warmup of {} leaves none to measure", source.name(), count, warmup));
    const ColorRange range = source.color_range();
    const bool against_reference = source.has_reference();
    const std::size_t shaders = resolve.size();
    // The frames the metrics compare, where the evaluator keeps them: a frame's truth alternates
    // between slots 0 and 1, and shader s's outputs between slots 2 + 2s and 3 + 2s, the other
    // one of each pair holding the frame before's.
    OutputStore& store = flip.store();
    auto truth_slot = [](std::size_t i) { return i % 2; };
    auto output_slot = [](std::size_t s, std::size_t i) { return 2 + 2 * s + i % 2; };
    std::vector<Meter> meters;
    for (std::size_t s = 0; s < shaders; ++s) meters.emplace_back(source, metrics);
    std::vector<FrameHandle> previous(shaders);
    FrameHandle previous_truth;
    auto each_shader = [&](auto step) -> Result<void> {
        for (std::size_t s = 0; s < shaders; ++s)
            if (auto ok = step(s); !ok) return fail(fmt::format("{}: {}", resolve.name(s), ok.error().message));
        return {};
    };
    FrameReader reader(resolve, source, warmup);
    for (std::size_t i = 0; i < count; ++i) {
        const std::string label = source.frame_label(i);
        // Outputs are checked from the frame before the first measured (its shimmer's previous) on.
        const bool check_outputs = i + 1 >= warmup, measured = i >= warmup;
        auto frame = reader.resolve(i, check_outputs && store.reads_back(), label);
        if (!frame) return std::unexpected(frame.error());
        if (check_outputs) {
            // What ghosting is measured against, on a measured frame.
            const FrameHandle truth = !measured           ? FrameHandle{}
                                      : against_reference ? store.put(truth_slot(i), std::move(*(*frame)->reference))
                                                          : store.put(truth_slot(i), std::move((*frame)->color));
            std::vector<FrameHandle> outputs(shaders);
            auto taken = each_shader([&](std::size_t s) -> Result<void> {
                auto output = store.take_output(output_slot(s, i), resolve, s, range, label);
                if (!output) return std::unexpected(output.error());
                outputs[s] = *output;
                return {};
            });
            if (!taken) return std::unexpected(taken.error());
            if (measured) {
                // A frame that starts a history has nothing before it to compare with.
                const bool starts = source.starts_history(i);
                for (std::size_t s = 0; s < shaders; ++s) meters[s].begin(i);
                // Metric by metric, each over every shader: a FLIP metric's shaders measured against
                // one truth in a row, whose FLIP work the device keeps from one to the next.
                for (std::size_t m = 0; m < metrics.size(); ++m) {
                    auto ok = each_shader([&](std::size_t s) -> Result<void> {
                        const MetricFrame frame{flip,
                                                range,
                                                truth,
                                                starts ? FrameHandle{} : previous_truth,
                                                outputs[s],
                                                starts ? FrameHandle{} : previous[s],
                                                maps && on_measured};
                        return meters[s].measure(m, frame, label);
                    });
                    if (!ok) return std::unexpected(ok.error());
                }
                if (on_output)
                    if (auto ok = each_shader([&](std::size_t s) -> Result<void> {
                            auto image = store.image(outputs[s]);
                            if (!image) return std::unexpected(image.error());
                            return on_output(s, i, **image);
                        });
                        !ok)
                        return std::unexpected(ok.error());
                if (on_measured)
                    if (auto ok = observe(store, meters, outputs, truth, source.name(), i, maps, on_measured); !ok)
                        return fail(fmt::format("{}: {}", label, ok.error().message));
            }
            previous = std::move(outputs);
            previous_truth = truth;
        }
        // For the interrupt tests: mid-pass, the first outputs measured, the next frame read ahead.
        if (i == warmup) test_hold_point("taa_pass");
        if (on_frame)
            if (auto ok = on_frame(); !ok) return std::unexpected(ok.error());
    }
    std::vector<SequenceMeasurement> measured;
    for (Meter& meter : meters) measured.push_back(meter.finish());
    return measured;
}

Result<SequenceMeasurement> measure_sequence(TaaResolve& resolve, const FrameSource& source, std::uint32_t warmup,
                                             FlipEvaluator& flip, const OutputObserver& on_output,
                                             const FrameObserver& on_frame, const Metrics& metrics) {
    ShaderOutputObserver first;
    if (on_output)
        first = [&](std::size_t s, std::size_t index, const Image& output) -> Result<void> {
            return s == 0 ? on_output(index, output) : Result<void>{};
        };
    auto measured = measure_sequence_all(resolve, source, warmup, flip, first, on_frame, {}, false, metrics);
    if (!measured) return std::unexpected(measured.error());
    return std::move(measured->front());
}

std::vector<double> scene_means(std::span<const double> still, std::span<const double> moving) {
    std::vector<double> means(std::max(still.size(), moving.size()), NAN);
    for (std::size_t m = 0; m < means.size(); ++m)
        means[m] = m < still.size() && !std::isnan(still[m]) ? still[m] : m < moving.size() ? moving[m] : NAN;
    return means;
}

Result<std::vector<TaaMeasurement>>
measure_scene_all(TaaResolve& resolve, const TaaScene& scene, const TaaSchedule& schedule, FlipEvaluator& flip,
                  const SceneShaderOutputObserver& on_output, const FrameObserver& on_frame,
                  const MeasuredFrameObserver& on_measured, bool maps, const Metrics& metrics) {
    std::vector<TaaMeasurement> m(resolve.size());
    const auto still = shimmer_frames(scene, schedule);
    const auto moving = ghosting_frames(scene, schedule);
    const std::uint32_t shown = scene.trail_frame(schedule);
    auto pass_on = [&](const FrameSource& source, bool keep_trail) -> ShaderOutputObserver {
        return [&, keep_trail](std::size_t s, std::size_t index, const Image& output) -> Result<void> {
            if (keep_trail && index == shown) m[s].trail = output;
            return on_output ? on_output(source.name(), s, index, output) : Result<void>{};
        };
    };
    auto shimmer = measure_sequence_all(resolve, *still, schedule.warmup, flip, pass_on(*still, false), on_frame,
                                        on_measured, maps, metrics);
    if (!shimmer) return std::unexpected(shimmer.error());
    auto ghosting = measure_sequence_all(resolve, *moving, schedule.warmup, flip, pass_on(*moving, true), on_frame,
                                         on_measured, maps, metrics);
    if (!ghosting) return std::unexpected(ghosting.error());
    for (std::size_t s = 0; s < m.size(); ++s) {
        m[s].means = scene_means((*shimmer)[s].means, (*ghosting)[s].means);
        m[s].against_reference = (*ghosting)[s].against_reference;
        m[s].per_frame = std::move((*shimmer)[s].per_frame);
        m[s].per_frame.insert(m[s].per_frame.end(), (*ghosting)[s].per_frame.begin(), (*ghosting)[s].per_frame.end());
    }
    return m;
}

Result<TaaMeasurement> measure_scene(TaaResolve& resolve, const TaaScene& scene, const TaaSchedule& schedule,
                                     FlipEvaluator& flip, const SceneOutputObserver& on_output,
                                     const FrameObserver& on_frame, const Metrics& metrics) {
    SceneShaderOutputObserver first;
    if (on_output)
        first = [&](const std::string& sequence, std::size_t s, std::size_t index, const Image& output) {
            return s == 0 ? on_output(sequence, index, output) : Result<void>{};
        };
    auto measured = measure_scene_all(resolve, scene, schedule, flip, first, on_frame, {}, false, metrics);
    if (!measured) return std::unexpected(measured.error());
    return std::move(measured->front());
}

} // namespace kdop
