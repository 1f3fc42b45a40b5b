#include "testbed/camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <numbers>

namespace kdop {

glm::mat4 view_projection(const Camera3d& camera, std::uint32_t width, std::uint32_t height) {
    glm::mat4 projection = glm::perspectiveRH_ZO(camera.fov_y, float(width) / float(height), kNearPlane, kFarPlane);
    projection[1][1] = -projection[1][1]; // y down, as Vulkan's framebuffer rows
    return projection * glm::lookAtRH(camera.eye, camera.target, glm::vec3(0, 1, 0));
}

glm::mat4 jittered(const glm::mat4& view_projection, glm::vec2 jitter, std::uint32_t width, std::uint32_t height) {
    // Moving the image by -jitter pixels brings what was at center + jitter to the center: in NDC
    // (2 units per frame), -2 * jitter / size. Adding offset * w to clip x and y (a row operation
    // on the matrix) moves the point by exactly offset after the divide by w, at every depth.
    const glm::vec2 offset = -2.0f * jitter / glm::vec2(float(width), float(height));
    glm::mat4 m = view_projection;
    for (int column = 0; column < 4; ++column) {
        m[column][0] += offset.x * m[column][3];
        m[column][1] += offset.y * m[column][3];
    }
    return m;
}

Camera3d camera_at(const Scene3d& scene, double time, bool pan) {
    Camera3d c = scene.camera;
    if (pan) {
        // 0.6 units either way over 240 frames: at most about 0.016 units a frame.
        const glm::vec3 offset(float(0.6 * std::sin(2 * std::numbers::pi * time / 240)), 0, 0);
        c.eye += offset;
        c.target += offset;
    }
    return c;
}

} // namespace kdop
