#include "testbed/scene3d_frames.h"

#include "sequence/jitter.h"

#include <fmt/format.h>

namespace kdop {

Camera3d Scene3dFrames::camera(std::size_t index) const {
    return camera_at(renderer_->scene(), double(index), timeline_.pan);
}

std::optional<glm::vec2> Scene3dFrames::jitter(std::size_t index) const {
    if (!timeline_.jitter) return std::nullopt;
    return r2_jitter(std::uint32_t(index));
}

std::string Scene3dFrames::frame_label(std::size_t index) const { return fmt::format("{}, frame {}", name_, index); }

Result<LoadedFrame> Scene3dFrames::frame(std::size_t index) const {
    // Motion points to the frame before (frame 0's to the instant before it, which a frame without
    // a history ignores).
    const double now = time(index), then = timeline_.animate ? double(index) - 1.0 : 0.0;
    const Camera3d camera_now = camera(index),
                   camera_then = camera_at(renderer_->scene(), double(index) - 1.0, timeline_.pan);
    auto drawn = renderer_->draw(now, camera_now, then, camera_then, jitter(index).value_or(glm::vec2(0)));
    if (!drawn) return fail(fmt::format("{}: {}", frame_label(index), drawn.error().message));
    LoadedFrame out;
    out.color = std::move(drawn->color);
    out.motion = std::move(drawn->motion);
    out.depth = Image(width(), height());
    for (std::size_t i = 0; i < drawn->depth.size(); ++i) out.depth->pixels[i] = glm::vec4(drawn->depth[i], 0, 0, 1);
    if (timeline_.reference_samples > 0) {
        // A box-filtered supersampled frame: the mean of the samples at the first R2 points.
        Image sum(width(), height(), glm::vec4(0));
        for (std::uint32_t s = 0; s < timeline_.reference_samples; ++s) {
            auto sample = renderer_->draw(now, camera_now, now, camera_now, r2_point(s));
            if (!sample) return fail(fmt::format("{}: reference: {}", frame_label(index), sample.error().message));
            for (std::size_t i = 0; i < sum.pixels.size(); ++i) sum.pixels[i] += sample->color.pixels[i];
        }
        for (glm::vec4& p : sum.pixels) p /= float(timeline_.reference_samples);
        out.reference = std::move(sum);
    }
    return out;
}

} // namespace kdop
