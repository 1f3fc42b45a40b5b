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

namespace {

FigureSpread spread(const std::vector<FrameFigures>& figures, double FrameFigures::*figure) {
    std::vector<double> values;
    for (const FrameFigures& f : figures)
        if (!std::isnan(f.*figure)) values.push_back(f.*figure);
    std::sort(values.begin(), values.end());
    return {quantile_of_sorted(values, 0.5), quantile_of_sorted(values, 0.95)};
}

} // namespace

FigureSpread ghosting_spread(const std::vector<FrameFigures>& figures) {
    return spread(figures, &FrameFigures::ghosting);
}
FigureSpread shimmer_spread(const std::vector<FrameFigures>& figures) {
    return spread(figures, &FrameFigures::shimmer);
}

FlipMean cpu_flip_mean(const HdrFlip& flip, const ExposureOptions& exposures) {
    return FlipMean{[&flip, exposures](const Image& reference, const Image& test, ColorRange range, bool map,
                                       bool) -> Result<FlipFigure> {
        if (range == ColorRange::ldr) { // LdrFlip::mean is the mean_error of this map
            auto error = flip.ldr().error_map(reference, test);
            if (!error) return std::unexpected(error.error());
            return FlipFigure{mean_error(*error), {}, map ? std::move(*error) : std::vector<float>{}};
        }
        auto maps = flip.maps(reference, test, exposures);
        if (!maps) return std::unexpected(maps.error());
        return FlipFigure{maps->mean, maps->range.note, map ? std::move(maps->error) : std::vector<float>{}};
    }};
}

FlipMean device_flip_mean(DeviceFlip& flip, const ExposureOptions& exposures) {
    return FlipMean{[&flip, exposures](const Image& reference, const Image& test, ColorRange range, bool map,
                                       bool same_reference) -> Result<FlipFigure> {
                        const auto kept =
                            same_reference ? DeviceFlip::Reference::unchanged : DeviceFlip::Reference::new_one;
                        if (range == ColorRange::ldr) {
                            auto evaluated = flip.ldr(reference, test, map, kept);
                            if (!evaluated) return std::unexpected(evaluated.error());
                            return FlipFigure{evaluated->mean, {}, std::move(evaluated->error)};
                        }
                        auto maps = flip.hdr(reference, test, exposures, map, kept);
                        if (!maps) return std::unexpected(maps.error());
                        return FlipFigure{maps->mean, maps->range.note, std::move(maps->error)};
                    },
                    &flip, exposures};
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

// One shader's measurement as the frames go by: its previous output, its sums and the notes it met.
// Its outputs are Images on the host, or, measured on the device (`on_device`), what DeviceFlip
// loaded there, with the previous one kept in the device's slot `slot`.
class Meter {
public:
    Meter(const FrameSource& source, const FlipMean& flip, bool on_device, std::size_t slot)
        : flip_(&flip), on_device_(on_device), slot_(slot), roles_(source.roles()) {
        m_.against_reference = source.has_reference();
        m_.range = source.color_range();
        sequence_ = source.name();
    }

    // Frame `i` is measured: ghosting() and shimmer() give its figures, in either order.
    void begin(std::size_t i) {
        m_.per_frame.push_back(FrameFigures{sequence_, i});
        ++m_.frames;
        map_.clear();
    }
    // The frame's output `current` (already within range; on the device, null: the one loaded
    // there) against `truth`; with `map`, the map of the figure maps_show_ghosting names is kept
    // (take_map()). `same_truth`: `truth` is the reference of the FLIP call before, unchanged
    // (FlipMean).
    Result<void> ghosting(const Image& truth, const Image* current, const std::string& label, bool map,
                          bool same_truth) {
        if (!roles_.ghosting) return {};
        const bool keep_map = map && maps_show_ghosting(roles_);
        auto ghosting = figure(
            label, m_.against_reference ? "ghosting against the reference" : "ghosting against the frame's color",
            keep_map, [&]() -> Result<FlipFigure> {
                if (!on_device_) return (*flip_)(truth, *current, m_.range, keep_map, same_truth);
                return loaded_figure(&truth, keep_map,
                                     same_truth ? DeviceFlip::Reference::unchanged : DeviceFlip::Reference::new_one);
            });
        if (!ghosting) return std::unexpected(ghosting.error());
        ghosting_sum_ += *ghosting;
        m_.per_frame.back().ghosting = *ghosting;
        return {};
    }
    // The same output against the one kept last (none where the frame starts a history).
    Result<void> shimmer(const Image* current, bool starts_history, const std::string& label, bool map) {
        if (!roles_.shimmer || starts_history) return {};
        const bool keep_map = map && !maps_show_ghosting(roles_);
        auto shimmer = figure(label, "shimmer against the previous output", keep_map, [&]() -> Result<FlipFigure> {
            if (!on_device_) return (*flip_)(previous_, *current, m_.range, keep_map, false);
            if (auto ok = flip_->device->load_kept(slot_, DeviceFlip::Input::reference); !ok)
                return std::unexpected(ok.error());
            return loaded_figure(nullptr, keep_map, DeviceFlip::Reference::new_one);
        });
        if (!shimmer) return std::unexpected(shimmer.error());
        shimmer_sum_ += *shimmer;
        ++shimmer_pairs_;
        m_.per_frame.back().shimmer = *shimmer;
        return {};
    }
    // Keeps the frame's output as the next one's previous: `output`, or on the device the one loaded.
    Result<void> keep(Image output) {
        if (on_device_) return flip_->device->keep(DeviceFlip::Input::test, slot_);
        previous_ = std::move(output);
        return {};
    }
    // The output kept last on the host (the frame's, once kept).
    const Image& output() const { return previous_; }
    const FrameFigures& last_figures() const { return m_.per_frame.back(); }
    // The map kept by the last measure() (empty where none was asked for or measured).
    std::vector<float> take_map() { return std::move(map_); }

    SequenceMeasurement finish() {
        for (const auto& [note, met] : notes_)
            m_.notes.push_back(met.more ? fmt::format("{} and {} more frame{}: {}", met.first_label, met.more,
                                                      met.more == 1 ? "" : "s", note)
                                        : fmt::format("{}: {}", met.first_label, note));
        m_.ghosting = roles_.ghosting ? ghosting_sum_ / double(m_.frames) : NAN;
        // Shimmer compares successive outputs of one history: where every measured frame starts a
        // new one (a camera cut on each), there is no pair, and the figure is absent, not 0.
        m_.shimmer = roles_.shimmer && shimmer_pairs_ ? shimmer_sum_ / double(shimmer_pairs_) : NAN;
        if (roles_.shimmer && !shimmer_pairs_)
            m_.notes.push_back("shimmer not measured: every measured frame starts a new history (a camera cut), "
                               "so no two successive outputs share one");
        return std::move(m_);
    }

private:
    // FLIP on the device of the output loaded there against `reference` (null: the one loaded).
    Result<FlipFigure> loaded_figure(const Image* reference, bool keep_map, DeviceFlip::Reference kept) {
        if (m_.range == ColorRange::hdr) {
            auto hdr = flip_->device->hdr_loaded(reference, flip_->exposures, keep_map, kept);
            if (!hdr) return std::unexpected(hdr.error());
            return FlipFigure{hdr->mean, hdr->range.note, std::move(hdr->error)};
        }
        auto ldr = flip_->device->ldr_loaded(reference, keep_map, kept);
        if (!ldr) return std::unexpected(ldr.error());
        return FlipFigure{ldr->mean, {}, std::move(ldr->error)};
    }
    // One figure of frame `label` as `evaluate` gives it, its error naming the frame and what was
    // measured.
    Result<double> figure(const std::string& label, const char* what, bool map,
                          const std::function<Result<FlipFigure>()>& evaluate) {
        auto figure = evaluate();
        if (!figure) return fail(fmt::format("{}: {}: {}", label, what, figure.error().message));
        if (!figure->note.empty()) {
            auto [it, first] = notes_.try_emplace(figure->note, Met{label, 0});
            if (!first) ++it->second.more;
        }
        if (map) map_ = std::move(figure->map);
        return figure->mean;
    }

    struct Met {
        std::string first_label;
        std::size_t more = 0;
    };
    const FlipMean* flip_;
    bool on_device_;
    std::size_t slot_;
    SequenceRoles roles_;
    std::string sequence_;
    SequenceMeasurement m_;
    Image previous_;
    std::vector<float> map_;
    double shimmer_sum_ = 0, ghosting_sum_ = 0;
    std::size_t shimmer_pairs_ = 0;
    std::map<std::string, Met> notes_; // by note
};

} // namespace

Result<std::vector<SequenceMeasurement>> measure_sequence_all(TaaResolve& resolve, const FrameSource& source,
                                                              std::uint32_t warmup, const FlipMean& flip,
                                                              const ShaderOutputObserver& on_output,
                                                              const std::function<void()>& on_frame,
                                                              const MeasuredFrameObserver& on_measured, bool maps) {
    const std::size_t count = source.frame_count();
    if (warmup >= count)
        return fail(
            fmt::format("{}: {} frames, and a warmup of {} leaves none to measure", source.name(), count, warmup));
    const ColorRange range = source.color_range();
    const bool against_reference = source.has_reference();
    // Measured on the device (the device's FLIP on the resolve's queue): each output is checked,
    // moved onto the range and measured where the resolve leaves it, and comes back only for an
    // observer; HDR-FLIP's exposure range comes from luminances found there.
    DeviceFlip* device = flip.device && &flip.device->context() == &resolve.context() ? flip.device : nullptr;
    if (device)
        if (auto ok = device->keep_slots(resolve.size()); !ok) return std::unexpected(ok.error());
    const bool observed = on_output || on_measured;
    std::vector<Meter> meters;
    for (std::size_t s = 0; s < resolve.size(); ++s) meters.emplace_back(source, flip, device != nullptr, s);
    // Files are read (and decoded) on a worker a frame ahead, in order, while the device works.
    std::optional<Prefetch<Result<LoadedFrame>>> ahead;
    if (source.reads_ahead()) ahead.emplace(count, 1, [&source](std::size_t i) { return source.frame(i); });
    // A source that draws on the device draws every frame straight into the resolve: motion and
    // depth never come back, color and reference only for the frames measured.
    const DeviceFrames* on_device = ahead ? nullptr : source.device_frames();
    for (std::size_t i = 0; i < count; ++i) {
        const std::string label = source.frame_label(i);
        // Outputs are checked from the frame before the first measured (its shimmer's previous)
        // on, and come back to the host for it unless measured on the device.
        const bool check_outputs = i + 1 >= warmup, read_outputs = check_outputs && !device;
        // Each frame is drawn or read once, and checked once where it reaches the host, whatever the
        // number of shaders.
        auto check = [&](const LoadedFrame& frame) -> Result<void> {
            if (auto ok = check_range(frame.color, range, label, "color"); !ok) return ok;
            if (frame.reference.has_value() != against_reference)
                return fail(fmt::format("{}: {} a reference, unlike the sequence's others; give every frame a "
                                        "reference or none",
                                        label, against_reference ? "has no" : "has"));
            if (i >= warmup && against_reference) return check_range(*frame.reference, range, label, "reference");
            return {};
        };
        std::optional<LoadedFrame> frame;
        if (on_device) {
            const bool measured = i >= warmup;
            auto drawn = resolve.advance_all(*on_device, i, source.starts_history(i), read_outputs, measured);
            if (!drawn) return fail(fmt::format("{}: {}", label, drawn.error().message));
            if (measured) {
                if (auto ok = check(*drawn); !ok) return std::unexpected(ok.error());
                frame = std::move(*drawn);
            }
        } else {
            auto read = ahead ? ahead->take() : source.frame(i);
            if (!read) return std::unexpected(read.error());
            if (auto ok = check(*read); !ok) return std::unexpected(ok.error());
            if (auto ok = resolve.advance_all(*read, source.starts_history(i), read_outputs); !ok)
                return fail(fmt::format("{}: {}", label, ok.error().message));
            frame = std::move(*read);
        }
        if (check_outputs) {
            // Each shader's output is moved onto the range and measured, then kept as the next
            // frame's "previous" (what the observer sees of the frame: the maps carry what it is
            // compared against).
            const bool measured = i >= warmup;
            const bool map = maps && on_measured;
            // What ghosting is measured against, on a measured frame.
            const Image* truth = !measured ? nullptr : against_reference ? &*frame->reference : &frame->color;
            std::vector<Image> outputs(resolve.size());
            auto each_shader = [&](auto step) -> Result<void> {
                for (std::size_t s = 0; s < resolve.size(); ++s)
                    if (auto ok = step(s); !ok) return fail(fmt::format("{}: {}", resolve.name(s), ok.error().message));
                return {};
            };
            // On the device each shader's output is loaded once and measured whole.
            auto on_the_device = [&](std::size_t s) -> Result<void> {
                auto view = resolve.output_on_device(s);
                if (!view) return std::unexpected(view.error());
                auto outside = device->load(DeviceFlip::Input::test, *view, range == ColorRange::hdr, kOutputRounding);
                if (!outside) return std::unexpected(outside.error());
                if (*outside) {
                    const DeviceFlip::Outside& o = **outside;
                    auto why = outside_range(o.value, range, label, o.x, o.y);
                    return fail(why ? *why
                                    : fmt::format("internal error: {}: pixel ({}, {}) is outside the range on the "
                                                  "device, not on the host",
                                                  label, o.x, o.y));
                }
                if (measured) {
                    meters[s].begin(i);
                    if (auto ok = meters[s].ghosting(*truth, nullptr, label, map, s > 0); !ok) return ok;
                    if (auto ok = meters[s].shimmer(nullptr, source.starts_history(i), label, map); !ok) return ok;
                    if (observed) outputs[s] = device->loaded(DeviceFlip::Input::test);
                    if (on_output)
                        if (auto ok = on_output(s, i, outputs[s]); !ok) return ok;
                }
                return meters[s].keep({});
            };
            if (device) {
                if (auto ok = each_shader(on_the_device); !ok) return std::unexpected(ok.error());
            } else {
                // On the host, every shader's ghosting first: each is measured against the same truth,
                // whose FLIP work the device keeps from one to the next.
                auto ghosting = each_shader([&](std::size_t s) -> Result<void> {
                    auto output = within_range(resolve.take_output(s), range, label);
                    if (!output) return std::unexpected(output.error());
                    outputs[s] = std::move(*output);
                    if (!measured) return {};
                    meters[s].begin(i);
                    return meters[s].ghosting(*truth, &outputs[s], label, map, s > 0);
                });
                if (!ghosting) return std::unexpected(ghosting.error());
                auto shimmer = each_shader([&](std::size_t s) -> Result<void> {
                    if (measured) {
                        if (auto ok = meters[s].shimmer(&outputs[s], source.starts_history(i), label, map); !ok)
                            return ok;
                        if (on_output)
                            if (auto ok = on_output(s, i, outputs[s]); !ok) return ok;
                    }
                    return meters[s].keep(std::move(outputs[s]));
                });
                if (!shimmer) return std::unexpected(shimmer.error());
            }
            if (on_measured && i >= warmup) {
                std::vector<FrameFigures> figures;
                std::vector<const Image*> shown_outputs;
                std::vector<std::vector<float>> frame_maps;
                for (std::size_t s = 0; s < resolve.size(); ++s) {
                    figures.push_back(meters[s].last_figures());
                    shown_outputs.push_back(device ? &outputs[s] : &meters[s].output());
                    if (maps) frame_maps.push_back(meters[s].take_map());
                }
                const MeasuredFrame shown{.sequence = source.name(),
                                          .index = i,
                                          .figures = figures,
                                          .outputs = shown_outputs,
                                          .maps = frame_maps,
                                          .truth = truth};
                if (auto ok = on_measured(shown); !ok) return fail(fmt::format("{}: {}", label, ok.error().message));
            }
        }
        // For the interrupt tests: mid-pass, the first outputs measured, the next frame read ahead.
        if (i == warmup) test_hold_point("taa_pass");
        if (on_frame) on_frame();
    }
    std::vector<SequenceMeasurement> measured;
    for (Meter& meter : meters) measured.push_back(meter.finish());
    return measured;
}

Result<SequenceMeasurement> measure_sequence(TaaResolve& resolve, const FrameSource& source, std::uint32_t warmup,
                                             const FlipMean& flip, const OutputObserver& on_output,
                                             const std::function<void()>& on_frame) {
    ShaderOutputObserver first;
    if (on_output)
        first = [&](std::size_t s, std::size_t index, const Image& output) -> Result<void> {
            return s == 0 ? on_output(index, output) : Result<void>{};
        };
    auto measured = measure_sequence_all(resolve, source, warmup, flip, first, on_frame);
    if (!measured) return std::unexpected(measured.error());
    return std::move(measured->front());
}

Result<std::vector<TaaMeasurement>> measure_scene_all(TaaResolve& resolve, const TaaScene& scene,
                                                      const TaaSchedule& schedule, const FlipMean& flip,
                                                      const SceneShaderOutputObserver& on_output,
                                                      const std::function<void()>& on_frame,
                                                      const MeasuredFrameObserver& on_measured, bool maps) {
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
                                        on_measured, maps);
    if (!shimmer) return std::unexpected(shimmer.error());
    auto ghosting = measure_sequence_all(resolve, *moving, schedule.warmup, flip, pass_on(*moving, true), on_frame,
                                         on_measured, maps);
    if (!ghosting) return std::unexpected(ghosting.error());
    for (std::size_t s = 0; s < m.size(); ++s) {
        m[s].shimmer = (*shimmer)[s].shimmer;
        m[s].ghosting = (*ghosting)[s].ghosting;
        m[s].against_reference = (*ghosting)[s].against_reference;
        m[s].per_frame = std::move((*shimmer)[s].per_frame);
        m[s].per_frame.insert(m[s].per_frame.end(), (*ghosting)[s].per_frame.begin(), (*ghosting)[s].per_frame.end());
    }
    return m;
}

Result<TaaMeasurement> measure_scene(TaaResolve& resolve, const TaaScene& scene, const TaaSchedule& schedule,
                                     const FlipMean& flip, const SceneOutputObserver& on_output,
                                     const std::function<void()>& on_frame) {
    SceneShaderOutputObserver first;
    if (on_output)
        first = [&](const std::string& sequence, std::size_t s, std::size_t index, const Image& output) {
            return s == 0 ? on_output(sequence, index, output) : Result<void>{};
        };
    auto measured = measure_scene_all(resolve, scene, schedule, flip, first, on_frame);
    if (!measured) return std::unexpected(measured.error());
    return std::move(measured->front());
}

} // namespace kdop
