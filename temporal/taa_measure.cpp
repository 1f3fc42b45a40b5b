#include "temporal/taa_measure.h"

#include "core/memory_budget.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace kdop {

Result<Image> within_range(const Image& frame, ColorRange range, std::string_view what) {
    constexpr float kRounding = 1e-4f;
    const bool hdr = range == ColorRange::hdr;
    Image out = frame;
    for (std::uint32_t y = 0; y < frame.height; ++y)
        for (std::uint32_t x = 0; x < frame.width; ++x) {
            glm::vec4& pixel = out.at(x, y);
            // Rounding scales with the colors the resolve blended: for HDR, the pixel's largest.
            const float scale = hdr ? std::max({1.0f, pixel.r, pixel.g, pixel.b}) : 1.0f;
            for (int c = 0; c < 3; ++c) {
                float& v = pixel[c];
                const bool within =
                    v >= -kRounding * scale && (hdr ? std::isfinite(scale) : v <= 1 + kRounding); // NaN fails
                if (!within)
                    return fail(fmt::format("{}: pixel ({}, {}) has {} {}, outside {} by more than rounding", what, x,
                                            y, "RGB"[c], v, hdr ? "[0, inf)" : "[0, 1]"));
                v = hdr ? std::max(v, 0.0f) : std::clamp(v, 0.0f, 1.0f);
            }
        }
    return out;
}

FlipMean cpu_flip_mean(const HdrFlip& flip, const ExposureOptions& exposures) {
    return [&flip, exposures](const Image& reference, const Image& test, ColorRange range) -> Result<FlipFigure> {
        if (range == ColorRange::ldr) {
            auto mean = flip.ldr().mean(reference, test);
            if (!mean) return std::unexpected(mean.error());
            return FlipFigure{*mean, {}};
        }
        auto maps = flip.maps(reference, test, exposures);
        if (!maps) return std::unexpected(maps.error());
        return FlipFigure{maps->mean, maps->range.note};
    };
}

FlipMean device_flip_mean(DeviceFlip& flip, const ExposureOptions& exposures) {
    return [&flip, exposures](const Image& reference, const Image& test, ColorRange range) -> Result<FlipFigure> {
        if (range == ColorRange::ldr) {
            auto mean = flip.mean(reference, test);
            if (!mean) return std::unexpected(mean.error());
            return FlipFigure{*mean, {}};
        }
        auto maps = flip.hdr(reference, test, exposures, false);
        if (!maps) return std::unexpected(maps.error());
        return FlipFigure{maps->mean, maps->range.note};
    };
}

Result<void> check_measurable(const Context& context, std::uint32_t width, std::uint32_t height, bool device_flip) {
    const std::uint32_t limit = context.properties().limits.maxImageDimension2D;
    if (width > limit || height > limit)
        return fail(fmt::format("{}x{} frames are larger than {} allows: at most {} pixels on a side", width, height,
                                context.device_name(), limit));
    if (device_flip)
        if (auto ok = DeviceFlip::check_limits(context, width, height); !ok)
            return fail(ok.error().message + "; --cpu-flip measures with the CPU's FLIP, which has no such limit");
    // The resolve's pass and its four inputs, a frame's images, the last output and its checked copy;
    // on lavapipe device memory is this process's memory.
    const std::uint64_t resolve = rectify_pass_bytes(width, height) + 6 * image_bytes(width, height);
    const std::uint64_t flip = device_flip ? DeviceFlip::bytes(width, height) : ldr_flip_bytes(width, height);
    return check_memory(fmt::format("measuring {}x{} frames", width, height), resolve + flip);
}

Result<Sequence> read_resolvable_sequence(const std::filesystem::path& dir, std::uint32_t warmup,
                                          const ResolveOptions& options) {
    auto sequence = read_sequence(dir);
    if (!sequence) return sequence;
    if (warmup >= sequence->frames.size())
        return fail(fmt::format("--sequence: {}: {} frames, and --warmup {} leaves none to measure", dir.string(),
                                sequence->frames.size(), warmup));
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

Result<SequenceMeasurement> measure_sequence(TaaResolve& resolve, const FrameSource& source, std::uint32_t warmup,
                                             const FlipMean& flip, TaaMetrics metrics, const OutputObserver& on_output,
                                             const std::function<void()>& on_frame) {
    const std::size_t count = source.frame_count();
    if (warmup >= count)
        return fail(
            fmt::format("{}: {} frames, and a warmup of {} leaves none to measure", source.name(), count, warmup));
    SequenceMeasurement m;
    m.against_reference = source.has_reference();
    m.range = source.color_range();
    Image previous;
    double shimmer_sum = 0, ghosting_sum = 0;
    std::size_t shimmer_pairs = 0;
    struct Met {
        std::string first_label;
        std::size_t more = 0;
    };
    std::map<std::string, Met> notes; // by note
    // One figure of frame `label`, its error naming the frame and what was measured.
    auto measured = [&](const Image& reference, const Image& test, const std::string& label,
                        const char* what) -> Result<double> {
        auto figure = flip(reference, test, m.range);
        if (!figure) return fail(fmt::format("{}: {}: {}", label, what, figure.error().message));
        if (!figure->note.empty()) {
            auto [it, first] = notes.try_emplace(figure->note, Met{label, 0});
            if (!first) ++it->second.more;
        }
        return figure->mean;
    };
    for (std::size_t i = 0; i < count; ++i) {
        auto frame = source.frame(i);
        if (!frame) return std::unexpected(frame.error());
        const std::string label = source.frame_label(i);
        if (auto ok = check_range(frame->color, m.range, label, "color"); !ok) return std::unexpected(ok.error());
        if (frame->reference.has_value() != m.against_reference)
            return fail(fmt::format("{}: {} a reference, unlike the sequence's others; give every frame a reference "
                                    "or none",
                                    label, m.against_reference ? "has no" : "has"));
        auto output = resolve.advance(*frame, source.starts_history(i));
        if (!output) return fail(fmt::format("{}: {}", label, output.error().message));
        if (i + 1 >= warmup) {
            auto current = within_range(**output, m.range, label);
            if (!current) return std::unexpected(current.error());
            if (i >= warmup) {
                const Image* truth = &frame->color;
                if (m.against_reference) {
                    if (auto ok = check_range(*frame->reference, m.range, label, "reference"); !ok)
                        return std::unexpected(ok.error());
                    truth = &*frame->reference;
                }
                if (metrics.ghosting) {
                    auto ghosting = measured(*truth, *current, label,
                                             m.against_reference ? "ghosting against the reference"
                                                                 : "ghosting against the frame's color");
                    if (!ghosting) return std::unexpected(ghosting.error());
                    ghosting_sum += *ghosting;
                }
                if (metrics.shimmer && !source.starts_history(i)) {
                    auto shimmer = measured(previous, *current, label, "shimmer against the previous output");
                    if (!shimmer) return std::unexpected(shimmer.error());
                    shimmer_sum += *shimmer;
                    ++shimmer_pairs;
                }
                ++m.frames;
                if (on_output)
                    if (auto ok = on_output(i, *current); !ok) return std::unexpected(ok.error());
            }
            previous = std::move(*current);
        }
        if (on_frame) on_frame();
    }
    for (const auto& [note, met] : notes)
        m.notes.push_back(met.more ? fmt::format("{} and {} more frame{}: {}", met.first_label, met.more,
                                                 met.more == 1 ? "" : "s", note)
                                   : fmt::format("{}: {}", met.first_label, note));
    m.ghosting = ghosting_sum / double(m.frames);
    m.shimmer = shimmer_pairs ? shimmer_sum / double(shimmer_pairs) : 0.0;
    return m;
}

Result<TaaMeasurement> measure_scene(TaaResolve& resolve, const TaaScene& scene, const TaaSchedule& schedule,
                                     const FlipMean& flip, const SceneOutputObserver& on_output,
                                     const std::function<void()>& on_frame) {
    TaaMeasurement m;
    const auto still = shimmer_frames(scene, schedule);
    auto pass_on = [&](const FrameSource& source) -> OutputObserver {
        if (!on_output) return {};
        return [&](std::size_t index, const Image& output) { return on_output(source.name(), index, output); };
    };
    auto shimmer = measure_sequence(resolve, *still, schedule.warmup, flip, {.shimmer = true, .ghosting = false},
                                    pass_on(*still), on_frame);
    if (!shimmer) return std::unexpected(shimmer.error());
    const auto moving = ghosting_frames(scene, schedule);
    const std::uint32_t shown = scene.trail_frame(schedule);
    const OutputObserver also_written = pass_on(*moving);
    auto keep_trail = [&](std::size_t index, const Image& output) -> Result<void> {
        if (index == shown) m.trail = output;
        return also_written ? also_written(index, output) : Result<void>{};
    };
    auto ghosting = measure_sequence(resolve, *moving, schedule.warmup, flip, {.shimmer = false, .ghosting = true},
                                     keep_trail, on_frame);
    if (!ghosting) return std::unexpected(ghosting.error());
    m.shimmer = shimmer->shimmer;
    m.ghosting = ghosting->ghosting;
    m.against_reference = ghosting->against_reference;
    return m;
}

} // namespace kdop
