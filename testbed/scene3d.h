// The testbed's scenes: what is in them and how it moves. A scene is a still mesh (the ground and
// what stands on it), a moving mesh rebuilt at any instant, a texture the ground is painted with,
// a sun and a camera; time is in frames. Every scene is procedural and seeded: the same seed gives
// the same scene, bit for bit.
//
// grass3d (the paper's "Grass"): a textured ground under tens of thousands of thin grass blades,
// each with its own hue and brightness, so edges alias and chroma varies at every pixel; a figure
// of boxes kicks in front of it, its kicking leg swinging across the view, over a dark contact
// shadow that also darkens the blades in it.
// asphalt3d (the paper's "Asphalt"): a road of high-frequency luma texture with few geometric
// edges (the dashes of a center line), a saturated red car driving back and forth across it on
// four near-black wheels that turn as they roll, with a dark shadow under it.
#pragma once

#include "images/image.h"
#include "testbed/mesh.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <functional>
#include <string>

namespace kdop {

struct Camera3d {
    glm::vec3 eye, target;
    float fov_y = 0.7f; // vertical field of view, radians
};

struct Scene3d {
    std::string name;
    std::string content;      // what it is made of, for reports: the texture, the counts, the seed
    Image texture;            // the ground's albedo, linear RGB in [0, 1], repeated
    float texture_period = 1; // world units per repeat of the texture
    Mesh still;
    std::function<Mesh(double time)> moving; // the same vertices, in the same order, at every time
    Camera3d camera;                         // at rest
    glm::vec3 sun{0, 1, 0};                  // unit, toward the sun
    float ambient = 0.35f;                   // the light a face turned away from the sun still gets
    glm::vec4 sky{0.5f, 0.6f, 0.75f, 1};     // where nothing is drawn
};

Scene3d grass3d_scene(std::uint64_t seed);
Scene3d asphalt3d_scene(std::uint64_t seed);

// The camera at `time`: at rest, or, with `pan`, sliding sideways on a slow sine path (eye and
// target together, so the view translates and what was behind the figure or car, or beyond the
// frame's border, comes into view).
Camera3d camera_at(const Scene3d& scene, double time, bool pan);

} // namespace kdop
