// The testbed camera's matrices, in Vulkan's conventions: clip y points down the image (row 0 at
// the top) and depth runs from 0 at the near plane to 1 at the far one, so nearer is smaller, as
// the sequence format's default "depth": {"nearer": "smaller"} says.
#pragma once

#include "testbed/scene3d.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include <cstdint>

namespace kdop {

inline constexpr float kNearPlane = 0.1f, kFarPlane = 200.0f;

// World to clip for `camera` on a width x height image.
glm::mat4 view_projection(const Camera3d& camera, std::uint32_t width, std::uint32_t height);

// `view_projection` with its image shifted so that each pixel's center samples what lies `jitter`
// pixels (x right, y down) from it: the jitter applied through the projection, as a renderer
// applies it.
glm::mat4 jittered(const glm::mat4& view_projection, glm::vec2 jitter, std::uint32_t width, std::uint32_t height);

} // namespace kdop
