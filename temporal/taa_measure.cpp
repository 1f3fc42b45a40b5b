#include "taa_measure.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace kdop {

Result<Image> within_unit_range(const Image& frame, std::string_view what) {
    constexpr float kRounding = 1e-4f;
    Image out = frame;
    for (std::uint32_t y = 0; y < frame.height; ++y)
        for (std::uint32_t x = 0; x < frame.width; ++x)
            for (int c = 0; c < 3; ++c) {
                float& v = out.at(x, y)[c];
                if (!(v >= -kRounding && v <= 1 + kRounding))
                    return fail(fmt::format("{}: pixel ({}, {}) has {} {}, outside [0, 1] by more than rounding", what,
                                            x, y, "RGB"[c], v));
                v = std::clamp(v, 0.0f, 1.0f);
            }
    return out;
}

std::uint32_t trail_frame(const TaaSchedule& schedule, std::uint32_t width, std::uint32_t height) {
    std::uint32_t best = schedule.warmup;
    float fastest = -1;
    for (std::uint32_t f = schedule.warmup; f < schedule.warmup + schedule.frames; ++f) {
        const float speed = std::abs(frame_state(f, width, height, true, false).car_motion.x);
        if (speed > fastest) fastest = speed, best = f;
    }
    return best;
}

TrailCrop trail_crop(const TaaSchedule& schedule, std::uint32_t width, std::uint32_t height) {
    const FrameState s = frame_state(trail_frame(schedule, width, height), width, height, true, false);
    TrailCrop crop{0, 0, std::max(width / 2, 1u), std::max(height / 2, 1u), 2};
    const float behind = s.car_motion.x > 0 ? -0.15f * float(width) : 0.15f * float(width);
    auto corner = [](float center, std::uint32_t side, std::uint32_t frame) {
        return std::uint32_t(std::clamp(center - float(side) / 2, 0.0f, float(frame - side)));
    };
    crop.x = corner(s.car_center.x + behind, crop.width, width);
    crop.y = corner(s.car_center.y, crop.height, height);
    return crop;
}

namespace {

// Refuses a color outside LDR-FLIP's range, naming where it is.
Result<void> check_ldr(const Image& image, const std::string& label, std::string_view what) {
    for (std::uint32_t y = 0; y < image.height; ++y)
        for (std::uint32_t x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float v = image.at(x, y)[c];
                if (!(v >= 0.0f && v <= 1.0f))
                    return fail(fmt::format("{}: {} pixel ({}, {}) has {} {}, outside [0, 1]; ghosting and shimmer "
                                            "are measured in LDR-FLIP, which takes linear values from 0 to 1, so an "
                                            "HDR sequence must be tone-mapped first (kdop does not clamp it)",
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
    Image previous;
    double shimmer_sum = 0, ghosting_sum = 0;
    std::size_t shimmer_pairs = 0;
    for (std::size_t i = 0; i < count; ++i) {
        auto frame = source.frame(i);
        if (!frame) return std::unexpected(frame.error());
        const std::string label = source.frame_label(i);
        if (auto ok = check_ldr(frame->color, label, "color"); !ok) return std::unexpected(ok.error());
        if (frame->reference.has_value() != m.against_reference)
            return fail(fmt::format("{}: {} a reference, unlike the sequence's others; give every frame a reference "
                                    "or none",
                                    label, m.against_reference ? "has no" : "has"));
        auto output = resolve.advance(*frame, source.starts_history(i));
        if (!output) return fail(fmt::format("{}: {}", label, output.error().message));
        if (i + 1 >= warmup) {
            auto current = within_unit_range(**output, label);
            if (!current) return std::unexpected(current.error());
            if (i >= warmup) {
                const Image* truth = &frame->color;
                if (m.against_reference) {
                    if (auto ok = check_ldr(*frame->reference, label, "reference"); !ok)
                        return std::unexpected(ok.error());
                    truth = &*frame->reference;
                }
                if (metrics.ghosting) {
                    auto ghosting = flip(*truth, *current);
                    if (!ghosting) return std::unexpected(ghosting.error());
                    ghosting_sum += *ghosting;
                }
                if (metrics.shimmer && !source.starts_history(i)) {
                    auto shimmer = flip(previous, *current);
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
    m.ghosting = ghosting_sum / double(m.frames);
    m.shimmer = shimmer_pairs ? shimmer_sum / double(shimmer_pairs) : 0.0;
    return m;
}

SceneFrames shimmer_frames(const std::string& name, const Image& background, const TaaSchedule& schedule) {
    return SceneFrames(name + "-shimmer", background, schedule.warmup + schedule.frames, false, true);
}

SceneFrames ghosting_frames(const std::string& name, const Image& background, const TaaSchedule& schedule) {
    return SceneFrames(name + "-ghosting", background, schedule.warmup + schedule.frames, true, false);
}

Result<TaaMeasurement> measure_scene(TaaResolve& resolve, const std::string& name, const Image& background,
                                     const TaaSchedule& schedule, const FlipMean& flip,
                                     const SceneOutputObserver& on_output, const std::function<void()>& on_frame) {
    TaaMeasurement m;
    const SceneFrames still = shimmer_frames(name, background, schedule);
    auto pass_on = [&](const FrameSource& source) -> OutputObserver {
        if (!on_output) return {};
        return [&](std::size_t index, const Image& output) { return on_output(source.name(), index, output); };
    };
    auto shimmer = measure_sequence(resolve, still, schedule.warmup, flip, {.shimmer = true, .ghosting = false},
                                    pass_on(still), on_frame);
    if (!shimmer) return std::unexpected(shimmer.error());
    const SceneFrames moving = ghosting_frames(name, background, schedule);
    const std::uint32_t shown = trail_frame(schedule, background.width, background.height);
    const OutputObserver also_written = pass_on(moving);
    auto keep_trail = [&](std::size_t index, const Image& output) -> Result<void> {
        if (index == shown) m.trail = output;
        return also_written ? also_written(index, output) : Result<void>{};
    };
    auto ghosting = measure_sequence(resolve, moving, schedule.warmup, flip, {.shimmer = false, .ghosting = true},
                                     keep_trail, on_frame);
    if (!ghosting) return std::unexpected(ghosting.error());
    m.shimmer = shimmer->shimmer;
    m.ghosting = ghosting->ghosting;
    return m;
}

} // namespace kdop
