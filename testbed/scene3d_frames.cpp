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

Camera3d Scene3dFrames::previous_camera(std::size_t index) const {
    return camera_at(renderer_->scene(), double(index) - 1.0, timeline_.pan);
}

Result<void> Scene3dFrames::draw_into(std::size_t index, const RasterTargets& targets) const {
    auto drawn = renderer_->draw_into(time(index), camera(index), previous_time(index), previous_camera(index),
                                      jitter(index).value_or(glm::vec2(0)), targets);
    if (!drawn) return fail(fmt::format("{}: {}", frame_label(index), drawn.error().message));
    return {};
}

Result<LoadedFrame> Scene3dFrames::frame(std::size_t index) const {
    const double now = time(index);
    const Camera3d camera_now = camera(index);
    auto drawn = renderer_->draw(now, camera_now, previous_time(index), previous_camera(index),
                                 jitter(index).value_or(glm::vec2(0)));
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
