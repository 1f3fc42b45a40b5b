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

Result<TaaMeasurement> measure_taa(TaaLoop& loop, std::uint32_t width, std::uint32_t height,
                                   const TaaSchedule& schedule, const LdrFlip& flip,
                                   const std::function<void()>& on_frame) {
    TaaMeasurement m;
    const std::uint32_t end = schedule.warmup + schedule.frames;

    // Shimmer: jitter on, no animation; frame `warmup - 1` is the first one compared against.
    loop.restart();
    Image previous;
    double shimmer_sum = 0;
    for (std::uint32_t f = 0; f < end; ++f) {
        auto frame = loop.advance(frame_state(f, width, height, false, true));
        if (!frame) return std::unexpected(frame.error());
        if (f + 1 >= schedule.warmup) {
            auto current = within_unit_range(**frame, "shimmer sequence");
            if (!current) return std::unexpected(current.error());
            if (f >= schedule.warmup) {
                auto d = flip.mean(previous, *current);
                if (!d) return std::unexpected(d.error());
                shimmer_sum += *d;
            }
            previous = std::move(*current);
        }
        if (on_frame) on_frame();
    }

    // Ghosting: jitter off, animation on, each frame against the aliased frame of the same instant.
    loop.restart();
    const std::uint32_t shown = trail_frame(schedule, width, height);
    double ghosting_sum = 0;
    for (std::uint32_t f = 0; f < end; ++f) {
        const FrameState state = frame_state(f, width, height, true, false);
        auto frame = loop.advance(state);
        if (!frame) return std::unexpected(frame.error());
        if (f >= schedule.warmup) {
            auto result = within_unit_range(**frame, "ghosting sequence");
            auto reference = loop.render(state);
            if (!reference) return std::unexpected(reference.error());
            auto aliased = within_unit_range(*reference, "aliased frame");
            if (!result || !aliased) return std::unexpected(result ? aliased.error() : result.error());
            auto d = flip.mean(*aliased, *result);
            if (!d) return std::unexpected(d.error());
            ghosting_sum += *d;
            if (f == shown) m.trail = std::move(*result);
        }
        if (on_frame) on_frame();
    }
    m.shimmer = shimmer_sum / schedule.frames;
    m.ghosting = ghosting_sum / schedule.frames;
    return m;
}

} // namespace kdop
