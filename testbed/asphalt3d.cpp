#include "testbed/scene3d.h"

#include "images/texture_cases.h"

#include <fmt/format.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <numbers>

namespace kdop {
namespace {

constexpr double kDrivePeriod = 72; // frames, there and back
constexpr float kDriveAmplitude = 3.0f, kWheelRadius = 0.34f;
const glm::vec3 kRed(0.62f, 0.018f, 0.012f), kWindow(0.03f, 0.035f, 0.045f), kTire(0.014f, 0.013f, 0.013f),
    kHub(0.09f, 0.09f, 0.095f), kShadow(0.01f, 0.01f, 0.01f), kPaint(0.7f, 0.66f, 0.45f);

double car_x(double time) { return kDriveAmplitude * std::sin(2 * std::numbers::pi * time / kDrivePeriod); }

// The car at `time`: its x on a sine path (it never jumps, and it is seen at every speed from rest
// to about 0.26 units a frame, 56 km/h at 60 Hz if a unit is a meter), the wheels turned by the distance rolled, and
// its shadow, which moves with it.
Mesh car(double time) {
    using glm::mat4, glm::vec3;
    const float x = float(car_x(time));
    Mesh mesh;
    add_ground_ellipse(mesh, 0.004f, {x, 0}, {2.45f, 1.15f}, kShadow);
    const mat4 body = glm::translate(mat4(1), vec3(x, 0, 0));
    add_box(mesh, glm::translate(body, vec3(0, 0.62f, 0)), vec3(2.1f, 0.34f, 0.9f), kRed);
    add_box(mesh, glm::translate(body, vec3(-0.25f, 1.2f, 0)), vec3(1.05f, 0.26f, 0.82f), kRed);
    // The windows: a dark band just outside the cabin's sides.
    add_box(mesh, glm::translate(body, vec3(-0.25f, 1.24f, 0)), vec3(0.9f, 0.14f, 0.83f), kWindow);
    // Rolling without slipping: the angle is the distance over the radius, clockwise seen from
    // +z when moving toward +x.
    const float angle = -x / kWheelRadius;
    for (float along : {-1.35f, 1.35f})
        for (float across : {-0.92f, 0.92f}) {
            const mat4 hub = glm::rotate(glm::translate(body, vec3(along, kWheelRadius, across)), angle, vec3(0, 0, 1));
            add_wheel(mesh, hub, kWheelRadius, 0.24f, 6, kTire, kHub);
        }
    return mesh;
}

} // namespace

Scene3d asphalt3d_scene(std::uint64_t seed) {
    Scene3d s;
    s.name = "asphalt3d";
    s.texture = make_texture(TextureFamily::asphalt, 256, 256, seed);
    s.texture_period = 3.0f;
    add_ground_quad(s.still, 0, {-60, -10}, {60, 80}, glm::vec3(0.8f), true);
    // A dashed center line beyond the car: the road's few other edges.
    for (float x = -30; x < 30; x += 3) add_ground_quad(s.still, 0.002f, {x, 2.6f}, {x + 1.5f, 2.75f}, kPaint, false);
    s.moving = car;
    s.camera = {{0, 2.4f, -4.7f}, {0, 0.6f, 0.5f}, 0.7f};
    s.sun = glm::normalize(glm::vec3(0.3f, 0.9f, -0.3f));
    s.content = fmt::format("road of kdop's asphalt texture family (256x256, seed {}, one repeat per {} units, no "
                            "mipmaps); a red car of 3 boxes on 4 turning wheels, driving back and forth",
                            seed, s.texture_period);
    return s;
}

} // namespace kdop
