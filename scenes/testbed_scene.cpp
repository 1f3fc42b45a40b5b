#include "scenes/testbed_scene.h"

#include "sequence/jitter.h"

#include "testbed/camera.h"
#include "testbed/scene3d_frames.h"

#include <fmt/format.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <vector>

namespace kdop {

Result<std::shared_ptr<TestbedScene>> TestbedScene::create(const Context& context, Scene3d scene, std::uint32_t width,
                                                           std::uint32_t height, bool camera_pan,
                                                           std::uint32_t reference_samples, double upscale) {
    if (upscale < 1) return fail(fmt::format("an upscaling ratio of {} (at least 1)", upscale));
    if (upscale > 1 && reference_samples == 0)
        return fail("frames drawn to be upscaled are measured against references at the output size: give them "
                    "reference samples");
    auto shared = std::make_shared<const Scene3d>(std::move(scene));
    auto input_side = [&](std::uint32_t side) {
        return std::max<std::uint32_t>(1, std::uint32_t(std::lround(double(side) / upscale)));
    };
    auto renderer = TestbedRenderer::create(context, shared, input_side(width), input_side(height));
    if (!renderer) return std::unexpected(renderer.error());
    std::shared_ptr<TestbedRenderer> frames(std::move(*renderer)), references = frames;
    if (upscale > 1) {
        auto output = TestbedRenderer::create(context, shared, width, height);
        if (!output) return std::unexpected(output.error());
        references = std::move(*output);
    }
    return std::shared_ptr<TestbedScene>(
        new TestbedScene(std::move(frames), std::move(references), camera_pan, reference_samples, upscale));
}

std::string TestbedScene::content() const {
    std::string s = "3-D, rasterized on the device: " + renderer_->scene().content;
    if (camera_pan_) s += "; the camera pans";
    if (reference_samples_ > 0) s += fmt::format("; references of {} samples per pixel", reference_samples_);
    if (upscale_ > 1)
        s += fmt::format("; drawn at {}x{}, jittered over {} Halton phases, to be upscaled {:g}x", renderer_->width(),
                         renderer_->height(), upscale_jitter_phases(upscale_), upscale_);
    return s;
}

std::shared_ptr<const FrameSource> TestbedScene::frames(const std::string& name, std::size_t count, bool animate,
                                                        bool jitter) const {
    return std::make_shared<Scene3dFrames>(
        name, renderer_, reference_renderer_,
        Scene3dTimeline{count, animate, jitter, camera_pan_, reference_samples_, upscale_});
}

TestbedScene::OnScreen TestbedScene::on_screen(double time) const {
    const Scene3d& scene = renderer_->scene();
    const glm::vec2 size(width(), height());
    if (!scene.moving) return {size * 0.5f, size * 0.5f, glm::vec2(0), size * 0.5f};
    auto project = [&](double t) {
        const glm::mat4 to_clip = view_projection(camera_at(scene, t, camera_pan_), width(), height());
        std::vector<glm::vec2> points;
        for (const MeshVertex& v : scene.moving(t)) {
            const glm::vec4 clip = to_clip * glm::vec4(v.position, 1);
            points.push_back((glm::vec2(clip) / clip.w * 0.5f + 0.5f) * size);
        }
        return points;
    };
    const std::vector<glm::vec2> now = project(time), before = project(time - 1);
    const glm::vec2 first = now.empty() ? size * 0.5f : now[0];
    OnScreen s{first, first, glm::vec2(0), first};
    glm::vec2 weighted(0);
    float weights = 0;
    for (std::size_t i = 0; i < now.size(); ++i) {
        s.low = glm::min(s.low, now[i]);
        s.high = glm::max(s.high, now[i]);
        s.motion += (now[i] - before[i]) / float(now.size());
        const float moved = glm::length(now[i] - before[i]);
        weighted += moved * now[i];
        weights += moved;
    }
    if (weights > 0) s.moving_center = weighted / weights;
    return s;
}

std::uint32_t TestbedScene::trail_frame(const TaaSchedule& schedule) const {
    std::uint32_t best = schedule.warmup;
    float fastest = -1;
    for (std::uint32_t f = schedule.warmup; f < schedule.warmup + schedule.frames; ++f) {
        const float speed = glm::length(on_screen(f).motion);
        if (speed > fastest) fastest = speed, best = f;
    }
    return best;
}

TrailCrop TestbedScene::trail_crop(const TaaSchedule& schedule) const {
    const OnScreen s = on_screen(trail_frame(schedule));
    TrailCrop crop{0, 0, std::max(width() / 2, 1u), std::max(height() / 2, 1u), 2};
    // Centered where the motion is, moved back by half the mesh's extent along the motion: a large
    // object's trailing edge and its trail, a small one whole with its trail.
    glm::vec2 center = s.moving_center;
    if (glm::length(s.motion) > 0) {
        const glm::vec2 direction = glm::normalize(s.motion);
        const float half_extent = 0.5f * glm::dot(glm::abs(direction), s.high - s.low);
        center -= direction * half_extent;
    }
    auto corner = [](float c, std::uint32_t side, std::uint32_t frame) {
        return std::uint32_t(std::clamp(c - float(side) / 2, 0.0f, float(frame - side)));
    };
    crop.x = corner(center.x, crop.width, width());
    crop.y = corner(center.y, crop.height, height());
    return crop;
}

} // namespace kdop
