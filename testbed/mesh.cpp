#include "testbed/mesh.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <array>
#include <cmath>
#include <numbers>

namespace kdop {
namespace {

void add_triangle(Mesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 normal, glm::vec3 albedo,
                  float textured = 0) {
    for (glm::vec3 p : {a, b, c}) mesh.push_back({p, normal, albedo, textured});
}

glm::vec3 transformed(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1)); }

glm::vec3 turned(const glm::mat4& m, glm::vec3 n) { return glm::normalize(glm::mat3(m) * n); }

} // namespace

void add_box(Mesh& mesh, const glm::mat4& transform, glm::vec3 half, glm::vec3 albedo) {
    // Each face: its normal axis and sign, and the two axes spanning it.
    for (int axis = 0; axis < 3; ++axis)
        for (float sign : {-1.0f, 1.0f}) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            std::array<glm::vec3, 4> corner;
            for (int i = 0; i < 4; ++i) {
                glm::vec3 p(0);
                p[axis] = sign * half[axis];
                p[u] = (i == 1 || i == 2 ? 1.0f : -1.0f) * half[u];
                p[v] = (i >= 2 ? 1.0f : -1.0f) * half[v];
                corner[i] = transformed(transform, p);
            }
            glm::vec3 n(0);
            n[axis] = sign;
            n = turned(transform, n);
            add_triangle(mesh, corner[0], corner[1], corner[2], n, albedo);
            add_triangle(mesh, corner[0], corner[2], corner[3], n, albedo);
        }
}

void add_ground_quad(Mesh& mesh, float height, glm::vec2 low, glm::vec2 high, glm::vec3 albedo, bool textured) {
    const glm::vec3 a(low.x, height, low.y), b(high.x, height, low.y), c(high.x, height, high.y),
        d(low.x, height, high.y);
    const glm::vec3 up(0, 1, 0);
    add_triangle(mesh, a, b, c, up, albedo, textured ? 1.0f : 0.0f);
    add_triangle(mesh, a, c, d, up, albedo, textured ? 1.0f : 0.0f);
}

void add_ground_ellipse(Mesh& mesh, float height, glm::vec2 center, glm::vec2 radii, glm::vec3 albedo) {
    constexpr int kSectors = 32;
    const glm::vec3 middle(center.x, height, center.y);
    auto rim = [&](int i) {
        const double a = 2 * std::numbers::pi * i / kSectors;
        return glm::vec3(center.x + radii.x * float(std::cos(a)), height, center.y + radii.y * float(std::sin(a)));
    };
    for (int i = 0; i < kSectors; ++i) add_triangle(mesh, middle, rim(i), rim(i + 1), {0, 1, 0}, albedo);
}

void add_wheel(Mesh& mesh, const glm::mat4& transform, float radius, float width, int spokes, glm::vec3 tire,
               glm::vec3 hub) {
    const int sectors = 2 * spokes;
    auto rim = [&](int i, float z) {
        const double a = 2 * std::numbers::pi * i / sectors;
        return glm::vec3(radius * float(std::cos(a)), radius * float(std::sin(a)), z);
    };
    const float h = width / 2;
    for (int i = 0; i < sectors; ++i) {
        const double mid = 2 * std::numbers::pi * (i + 0.5) / sectors;
        const glm::vec3 out = turned(transform, {float(std::cos(mid)), float(std::sin(mid)), 0});
        const glm::vec3 a = transformed(transform, rim(i, -h)), b = transformed(transform, rim(i + 1, -h)),
                        c = transformed(transform, rim(i + 1, h)), d = transformed(transform, rim(i, h));
        add_triangle(mesh, a, b, c, out, tire);
        add_triangle(mesh, a, c, d, out, tire);
        const glm::vec3 sector_color = i % 2 ? hub : tire;
        for (float side : {-h, h}) {
            add_triangle(mesh, transformed(transform, {0, 0, side}), transformed(transform, rim(i, side)),
                         transformed(transform, rim(i + 1, side)), turned(transform, {0, 0, side > 0 ? 1 : -1}),
                         sector_color);
        }
    }
}

} // namespace kdop
