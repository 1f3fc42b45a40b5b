#include "testbed_scene.h"

#include "camera.h"
#include "scene3d_frames.h"

#include <fmt/format.h>

#include <glm/geometric.hpp>

#include <algorithm>

namespace kdop {

Result<std::shared_ptr<TestbedScene>> TestbedScene::create(const Context& context, Scene3d scene,
                                                           std::uint32_t width, std::uint32_t height,
                                                           bool camera_pan, std::uint32_t reference_samples) {
    auto renderer = TestbedRenderer::create(context, std::make_shared<const Scene3d>(std::move(scene)), width, height);
    if (!renderer) return std::unexpected(renderer.error());
    return std::shared_ptr<TestbedScene>(
        new TestbedScene(std::shared_ptr<TestbedRenderer>(std::move(*renderer)), camera_pan, reference_samples));
}

std::string TestbedScene::content() const {
    std::string s = "3-D, rasterized on the device: " + renderer_->scene().content;
    if (camera_pan_) s += "; the camera pans";
    if (reference_samples_ > 0) s += fmt::format("; references of {} samples per pixel", reference_samples_);
    return s;
}

std::shared_ptr<const FrameSource> TestbedScene::frames(const std::string& name, std::size_t count, bool animate,
                                                        bool jitter) const {
    return std::make_shared<Scene3dFrames>(name, renderer_,
                                           Scene3dTimeline{count, animate, jitter, camera_pan_, reference_samples_});
}

std::pair<glm::vec2, glm::vec2> TestbedScene::screen_motion(double time) const {
    const Scene3d& scene = renderer_->scene();
    if (!scene.moving) return {glm::vec2(width(), height()) * 0.5f, glm::vec2(0)};
    auto mean_on_screen = [&](double t) {
        const glm::mat4 to_clip = view_projection(camera_at(scene, t, camera_pan_), width(), height());
        glm::vec2 sum(0);
        const Mesh mesh = scene.moving(t);
        for (const MeshVertex& v : mesh) {
            const glm::vec4 clip = to_clip * glm::vec4(v.position, 1);
            sum += (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(width(), height());
        }
        return sum / float(std::max<std::size_t>(mesh.size(), 1));
    };
    const glm::vec2 now = mean_on_screen(time);
    return {now, now - mean_on_screen(time - 1)};
}

std::uint32_t TestbedScene::trail_frame(const TaaSchedule& schedule) const {
    std::uint32_t best = schedule.warmup;
    float fastest = -1;
    for (std::uint32_t f = schedule.warmup; f < schedule.warmup + schedule.frames; ++f) {
        const float speed = glm::length(screen_motion(f).second);
        if (speed > fastest) fastest = speed, best = f;
    }
    return best;
}

TrailCrop TestbedScene::trail_crop(const TaaSchedule& schedule) const {
    const auto [center, motion] = screen_motion(trail_frame(schedule));
    TrailCrop crop{0, 0, std::max(width() / 2, 1u), std::max(height() / 2, 1u), 2};
    const glm::vec2 behind = glm::length(motion) > 0 ? -0.15f * float(width()) * glm::normalize(motion) : glm::vec2(0);
    auto corner = [](float c, std::uint32_t side, std::uint32_t frame) {
        return std::uint32_t(std::clamp(c - float(side) / 2, 0.0f, float(frame - side)));
    };
    crop.x = corner(center.x + behind.x, crop.width, width());
    crop.y = corner(center.y + behind.y, crop.height, height());
    return crop;
}

} // namespace kdop
