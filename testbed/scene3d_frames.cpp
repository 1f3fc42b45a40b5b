#include "testbed/scene3d_frames.h"

#include "sequence/jitter.h"
#include "testbed/camera.h"

#include <cmath>

#include <fmt/format.h>

namespace kdop {

Camera3d Scene3dFrames::camera(std::size_t index) const {
    return camera_at(renderer_->scene(), double(index), timeline_.pan);
}

std::optional<glm::vec2> Scene3dFrames::jitter(std::size_t index) const {
    if (timeline_.upscale > 1) return halton_jitter(std::uint32_t(index), upscale_jitter_phases(timeline_.upscale));
    if (!timeline_.jitter) return std::nullopt;
    return r2_jitter(std::uint32_t(index));
}

std::string Scene3dFrames::frame_label(std::size_t index) const { return fmt::format("{}, frame {}", name_, index); }

Camera3d Scene3dFrames::previous_camera(std::size_t index) const {
    return camera_at(renderer_->scene(), double(index) - 1.0, timeline_.pan);
}

Result<Image> Scene3dFrames::reference(std::size_t index) const {
    if (still() && still_reference_) return *still_reference_;
    const double now = time(index);
    const Camera3d camera_now = camera(index);
    Image sum(width(), height(), glm::vec4(0));
    for (std::uint32_t s = 0; s < timeline_.reference_samples; ++s) {
        // Only the color of a sample comes back.
        Image sample;
        if (auto ok = reference_renderer_->draw_into(now, camera_now, now, camera_now, r2_point(s), {}, &sample); !ok)
            return fail(fmt::format("{}: reference: {}", frame_label(index), ok.error().message));
        for (std::size_t i = 0; i < sum.pixels.size(); ++i) sum.pixels[i] += sample.pixels[i];
    }
    for (glm::vec4& p : sum.pixels) p /= float(timeline_.reference_samples);
    if (still()) still_reference_ = sum;
    return sum;
}

Result<LoadedFrame> Scene3dFrames::draw_into(std::size_t index, const RasterTargets& targets, bool read_back) const {
    LoadedFrame out;
    out.jitter = jitter(index).value_or(glm::vec2(0));
    auto drawn = renderer_->draw_into(time(index), camera(index), previous_time(index), previous_camera(index),
                                      jitter(index).value_or(glm::vec2(0)), targets, read_back ? &out.color : nullptr);
    if (!drawn) return fail(fmt::format("{}: {}", frame_label(index), drawn.error().message));
    if (read_back && timeline_.reference_samples > 0) {
        auto reference_image = reference(index);
        if (!reference_image) return std::unexpected(reference_image.error());
        out.reference = std::move(*reference_image);
    }
    return out;
}

Result<LoadedFrame> Scene3dFrames::frame(std::size_t index) const {
    auto drawn = renderer_->draw(time(index), camera(index), previous_time(index), previous_camera(index),
                                 jitter(index).value_or(glm::vec2(0)));
    if (!drawn) return fail(fmt::format("{}: {}", frame_label(index), drawn.error().message));
    LoadedFrame out;
    out.jitter = jitter(index).value_or(glm::vec2(0));
    out.color = std::move(drawn->color);
    out.motion = std::move(drawn->motion);
    out.depth = Image(input_width(), input_height()); // drawn at the input size, as color and motion
    for (std::size_t i = 0; i < drawn->depth.size(); ++i) out.depth->pixels[i] = glm::vec4(drawn->depth[i], 0, 0, 1);
    if (timeline_.reference_samples > 0) {
        auto reference_image = reference(index);
        if (!reference_image) return std::unexpected(reference_image.error());
        out.reference = std::move(*reference_image);
    }
    return out;
}

Result<std::vector<glm::vec2>> Scene3dFrames::output_motion(std::size_t index) const {
    // The same instants and cameras as the frame's own motion, drawn at the output size without
    // jitter: what NSS's motion_gt is ("Non-Jittered, output resolution velocity"). Only the
    // motion is kept; the color of this draw is not a reference (one sample per pixel).
    auto drawn = reference_renderer_->draw(time(index), camera(index), previous_time(index), previous_camera(index),
                                           glm::vec2(0));
    if (!drawn) return fail(fmt::format("{}: output-size motion: {}", frame_label(index), drawn.error().message));
    return std::move(drawn->motion);
}

std::optional<FrameCamera> Scene3dFrames::camera_of(std::size_t index) const {
    const Camera3d c = camera(index);
    const float aspect = float(width()) / float(height());
    return FrameCamera{.fov_x = 2.0f * std::atan(std::tan(c.fov_y / 2.0f) * aspect),
                       .fov_y = c.fov_y,
                       .near_plane = kNearPlane,
                       .far_plane = kFarPlane,
                       .view_projection = view_projection(c, width(), height())};
}

} // namespace kdop
