// Draws a testbed scene (scene3d.h) on the device through the runtime's raster pass: the color a
// renderer without TAA shows (one sample per pixel, at the pixel's center plus the jitter, the
// jitter applied through the projection), the motion of the surface seen at each pixel back to
// where it was at an earlier instant (from both instants' object and camera transforms, without
// jitter, as renderers compute it), and the depth.
#pragma once

#include "core/result.h"
#include "runtime/context.h"
#include "runtime/raster_pass.h"
#include "testbed/scene3d.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace kdop {

class TestbedRenderer {
public:
    // Builds the shaders (glslang, SPIRV-Tools' validator, then reflection) and uploads the still
    // mesh and the texture. `context` must outlive the renderer.
    static Result<std::unique_ptr<TestbedRenderer>> create(const Context& context, std::shared_ptr<const Scene3d> scene,
                                                           std::uint32_t width, std::uint32_t height);

    const Scene3d& scene() const { return *scene_; }
    std::uint32_t width() const { return width_; }
    std::uint32_t height() const { return height_; }

    // The scene at `time` seen by `camera`, sampled at each pixel's center + `jitter` (pixels, x
    // right, y down); motion in pixels toward where each surface was at `previous_time`, seen by
    // `previous_camera` (y down); depth from 0 (near) to 1 (far, or nothing drawn).
    Result<RasterImages> draw(double time, const Camera3d& camera, double previous_time,
                              const Camera3d& previous_camera, glm::vec2 jitter);
    // The same frame left on the device, copied into `targets`, and with `color_back` its color
    // read back (RasterPass::draw_into).
    Result<void> draw_into(double time, const Camera3d& camera, double previous_time, const Camera3d& previous_camera,
                           glm::vec2 jitter, const RasterTargets& targets, Image* color_back = nullptr);

private:
    TestbedRenderer() = default;
    // The moving mesh at `time` and `previous_time` on the device, and the uniform block's bytes.
    Result<std::vector<std::byte>> prepare(double time, const Camera3d& camera, double previous_time,
                                           const Camera3d& previous_camera, glm::vec2 jitter);

    std::shared_ptr<const Scene3d> scene_;
    std::uint32_t width_ = 0, height_ = 0;
    std::unique_ptr<RasterPass> pass_;
};

} // namespace kdop
