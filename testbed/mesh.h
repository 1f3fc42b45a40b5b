// The testbed's geometry: triangle lists of lit, colored vertices, and the shapes its scenes are
// built of. A mesh that moves is rebuilt at each instant with the same vertices in the same order,
// so that a vertex's two positions (this frame's and the last one's) give its motion exactly.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace kdop {

struct MeshVertex {
    glm::vec3 position; // world units, y up
    glm::vec3 normal;   // unit; the shader turns it toward the camera (every face is two-sided)
    glm::vec3 albedo;   // linear RGB in [0, 1]
    float textured = 0; // 1: the albedo is multiplied by the scene's texture at the position's x and z
};

using Mesh = std::vector<MeshVertex>; // every three vertices a triangle

// An axis-aligned box from -half to +half, then `transform`.
void add_box(Mesh& mesh, const glm::mat4& transform, glm::vec3 half, glm::vec3 albedo);

// A flat quad on the plane y = `height`, from `low` to `high` in x and z, facing up.
void add_ground_quad(Mesh& mesh, float height, glm::vec2 low, glm::vec2 high, glm::vec3 albedo, bool textured);

// A flat ellipse on the plane y = `height` around `center` (x, z) with radii `radii`, facing up:
// a contact shadow.
void add_ground_ellipse(Mesh& mesh, float height, glm::vec2 center, glm::vec2 radii, glm::vec3 albedo);

// A wheel: a cylinder of `radius` and `width` along its local z axis, then `transform`. The tread
// is `tire`; each side face is a fan of `spokes` sectors alternating `tire` and `hub`, so that a
// turning wheel shows its rotation.
void add_wheel(Mesh& mesh, const glm::mat4& transform, float radius, float width, int spokes, glm::vec3 tire,
               glm::vec3 hub);

} // namespace kdop
