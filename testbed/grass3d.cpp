#include "testbed/scene3d.h"

#include "images/random.h"
#include "images/texture_cases.h"

#include <fmt/format.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <numbers>

namespace kdop {
namespace {

constexpr int kBlades = 30000;
constexpr double kKickPeriod = 28; // frames per kick, out and back: about half a second at 60 Hz
// The figure stands at the origin facing +x, side-on to the camera, which looks along +z: its
// kick sweeps across the view.
const glm::vec2 kShadowCenter(0.05f, 0.0f), kShadowRadii(0.55f, 0.3f);
const glm::vec3 kShirt(0.55f, 0.56f, 0.58f), kTrousers(0.035f, 0.035f, 0.045f), kSkin(0.6f, 0.38f, 0.28f),
    kShoes(0.012f, 0.011f, 0.01f), kShadow(0.012f, 0.012f, 0.01f);

// Grass blades over the part of the ground the camera sees (a trapezoid widening with distance),
// each a thin triangle leaning its own way, with its own height, hue and brightness.
void add_blades(Mesh& mesh, std::uint64_t seed) {
    Random random(seed * 0x2545f4914f6cdd1dull + 17);
    const glm::vec3 green(0.09f, 0.30f, 0.04f), yellow(0.32f, 0.36f, 0.07f), blue_green(0.05f, 0.24f, 0.10f);
    for (int i = 0; i < kBlades; ++i) {
        const float z = float(random.uniform(-1.5, 14.0));
        const float half_width = 0.75f * (z + 3.4f) + 0.8f;
        const float x = float(random.uniform(-half_width, half_width));
        const float height = float(random.uniform(0.12, 0.36)), width = float(random.uniform(0.018, 0.04));
        const double facing = random.uniform(0, std::numbers::pi);
        const double lean_angle = random.uniform(0, 2 * std::numbers::pi);
        const glm::vec2 lean =
            float(random.uniform(0, 0.35)) * height * glm::vec2(std::cos(lean_angle), std::sin(lean_angle));
        const double hue = random.uniform(), brightness = random.uniform(0.55, 1.35);
        glm::vec3 albedo =
            hue < 0.5 ? glm::mix(green, yellow, float(hue * 2)) : glm::mix(green, blue_green, float(hue * 2 - 1));
        albedo *= float(brightness);
        const glm::vec2 d = (glm::vec2(x, z) - kShadowCenter) / kShadowRadii;
        if (glm::dot(d, d) < 1.0f) albedo *= 0.12f; // in the figure's shadow
        const glm::vec3 side(float(std::cos(facing)) * width, 0, float(std::sin(facing)) * width);
        const glm::vec3 base(x, 0, z), tip = base + glm::vec3(lean.x, height, lean.y);
        const glm::vec3 normal = glm::normalize(glm::cross(side, tip - base));
        for (glm::vec3 p : {base - side, base + side, tip}) mesh.push_back({p, normal, albedo, 0});
    }
}

// The figure at `time`: boxes for the torso, head, arms and legs; the right leg kicks forward and
// back, bending at the knee on the way back, the arms swing against it and the torso leans.
Mesh figure(double time) {
    using glm::mat4, glm::vec3;
    const double phase = 2 * std::numbers::pi * time / kKickPeriod;
    const float kick = float(0.95 * std::sin(phase)), knee = float(0.8 * std::max(0.0, -std::sin(phase))),
                lean = float(-0.12 * std::sin(phase));
    Mesh mesh;
    const vec3 z_axis(0, 0, 1); // the figure faces +x: its legs swing about z
    const mat4 hips = glm::rotate(glm::translate(mat4(1), vec3(0, 0.95f, 0)), lean, z_axis);
    add_box(mesh, glm::translate(hips, vec3(0, 0.33f, 0)), vec3(0.13f, 0.32f, 0.22f), kShirt);
    add_box(mesh, glm::translate(hips, vec3(0.02f, 0.78f, 0)), vec3(0.11f, 0.12f, 0.1f), kSkin);
    for (float side : {-1.0f, 1.0f}) {
        // Legs: the right one (side +1, nearer the camera) kicks; the left one stands.
        const float swing = side > 0 ? kick : 0.0f, bend = side > 0 ? knee : 0.0f;
        const mat4 hip = glm::rotate(glm::translate(mat4(1), vec3(0, 0.95f, side * 0.11f)), swing, z_axis);
        add_box(mesh, glm::translate(hip, vec3(0, -0.23f, 0)), vec3(0.08f, 0.23f, 0.08f), kTrousers);
        const mat4 knee_joint = glm::rotate(glm::translate(hip, vec3(0, -0.47f, 0)), -bend, z_axis);
        add_box(mesh, glm::translate(knee_joint, vec3(0, -0.22f, 0)), vec3(0.065f, 0.22f, 0.065f), kTrousers);
        add_box(mesh, glm::translate(knee_joint, vec3(0.06f, -0.45f, 0)), vec3(0.13f, 0.035f, 0.06f), kShoes);
        // Arms: swing against the kick.
        const mat4 shoulder =
            glm::rotate(glm::translate(hips, vec3(0, 0.6f, side * 0.29f)), -side * kick * 0.6f, z_axis);
        add_box(mesh, glm::translate(shoulder, vec3(0, -0.27f, 0)), vec3(0.055f, 0.27f, 0.055f), kShirt);
        add_box(mesh, glm::translate(shoulder, vec3(0, -0.6f, 0)), vec3(0.045f, 0.07f, 0.045f), kSkin);
    }
    return mesh;
}

} // namespace

Scene3d grass3d_scene(std::uint64_t seed) {
    Scene3d s;
    s.name = "grass3d";
    s.texture = make_texture(TextureFamily::grass, 256, 256, seed);
    s.texture_period = 4.0f;
    add_ground_quad(s.still, 0, {-150, -10}, {150, 190}, glm::vec3(0.55f), true);
    add_ground_ellipse(s.still, 0.004f, kShadowCenter, kShadowRadii, kShadow);
    add_blades(s.still, seed);
    s.moving = figure;
    s.camera = {{0.3f, 1.7f, -2.2f}, {0.3f, 0.85f, 0.4f}, 0.7f};
    s.sun = glm::normalize(glm::vec3(-0.4f, 0.85f, -0.35f));
    s.content = fmt::format("ground of kdop's grass texture family (256x256, seed {0}, one repeat per {1} units, "
                            "no mipmaps) under {2} grass blades (seed {0}); a figure of {3} boxes kicking",
                            seed, s.texture_period, kBlades, figure(0).size() / 36);
    return s;
}

} // namespace kdop
