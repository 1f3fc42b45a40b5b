// The fitting objective's k-DOP volume (fit/kdop_polytope.h) against what it must equal: boxes
// worked out by hand, the supplement's k-DOP volumes around the unit sphere, and Qhull's half-space
// intersection (accuracy/volume.h) on random neighborhoods; its faces against the volume they bound.
#include "accuracy/volume.h"
#include "fit/kdop_polytope.h"
#include "generator/axis_set.h"
#include "generator/variant_spec.h"
#include "images/random.h"
#include "reference/cpu_clip.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <vector>

namespace kdop {
namespace {

std::vector<glm::dvec3> builtin_axes(const char* name) {
    auto set = resolve_axis_set(name);
    EXPECT_TRUE(set) << name;
    return unit_axes(*set);
}

// The k-DOP around the unit sphere, from the slabs [-1, 1] given as such.
double sphere_volume(const KdopPolytope& kdop) {
    const std::vector<double> lo(kdop.axis_count(), -1.0), hi(kdop.axis_count(), 1.0);
    return kdop.volume(lo, hi);
}

TEST(KdopPolytope, BoxesHaveTheVolumeOfTheirSides) {
    const std::vector<glm::dvec3> xyz{{1, 0, 0}, {0, 2, 0}, {0, 0, 5}}; // lengths do not matter
    KdopPolytope box(xyz);
    EXPECT_DOUBLE_EQ(box.volume(std::vector<double>{0, -1, 2}, std::vector<double>{1, 1, 5}), 1.0 * 2 * 3);
    EXPECT_EQ(box.volume(std::vector<double>{0, 0, 0}, std::vector<double>{1, 0, 1}), 0.0) << "a slab of no width";
    // A left-handed order of the same axes, and a fourth axis that cuts off a corner of the unit cube.
    KdopPolytope cut(std::vector<glm::dvec3>{{0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {1, 1, 1}});
    EXPECT_NEAR(cut.volume(std::vector<double>{0, 0, 0, 0}, std::vector<double>{1, 1, 1, 2.5 / std::sqrt(3.0)}),
                1.0 - 0.125 / 6.0, 1e-12)
        << "the cube less the corner tetrahedron beyond x + y + z = 2.5 (legs 0.5)";
}

TEST(KdopPolytope, TheSupplementsKdopsAroundTheUnitSphereHaveItsVolumes) {
    // The volumes the supplement and issue 14 give for its general sets.
    EXPECT_NEAR(sphere_volume(KdopPolytope(builtin_axes("dop32"))), 4.6396, 5e-5);
    EXPECT_NEAR(sphere_volume(KdopPolytope(builtin_axes("dop22"))), 4.8589, 5e-5);
    EXPECT_DOUBLE_EQ(sphere_volume(KdopPolytope(builtin_axes("aabb"))), 8.0);
}

TEST(KdopPolytope, MatchesQhullOnRandomNeighborhoodsAndItsFacesBoundIt) {
    Random random(20261201);
    std::size_t checked = 0;
    for (const char* name : {"aabb", "ycocg", "dop16-grass", "dop16-asphalt", "dop22", "dop32"}) {
        const std::vector<glm::dvec3> axes = builtin_axes(name);
        KdopPolytope kdop(axes);
        std::vector<KdopPolytope::Face> faces(2 * axes.size());
        for (int trial = 0; trial < 200; ++trial) {
            // Nine colors around a random center, at a random scale (LDR to HDR), some nearly flat.
            const double scale = std::pow(10.0, random.uniform(-3, 3));
            const glm::dvec3 center(random.uniform(0, 4) * scale, random.uniform(0, 4) * scale,
                                    random.uniform(0, 4) * scale);
            const double flat = trial % 5 == 0 ? 1e-6 : 1.0;
            std::vector<glm::dvec3> points;
            for (int i = 0; i < 9; ++i)
                points.push_back(center + scale * glm::dvec3(random.uniform(-1, 1), random.uniform(-1, 1),
                                                             flat * random.uniform(-1, 1)));
            const double volume = kdop.volume_of(points, faces);

            std::vector<ReferenceSlab> slabs;
            for (const glm::dvec3& a : axes) {
                double lo = 1e300, hi = -1e300;
                for (const glm::dvec3& p : points) {
                    lo = std::min(lo, glm::dot(a, p));
                    hi = std::max(hi, glm::dot(a, p));
                }
                slabs.push_back({a, lo, hi});
            }
            glm::dvec3 mean(0.0);
            for (const glm::dvec3& p : points) mean += p / 9.0;
            auto qhull = slab_volume(slabs, mean);
            ASSERT_TRUE(qhull) << qhull.error().message;
            const double cube = std::pow(scale, 3);
            EXPECT_NEAR(volume, *qhull, 1e-9 * cube + 1e-9 * *qhull) << name << " trial " << trial;

            // The faces' areas and centroids give the volume again, as a sum of pyramids from the mean.
            double from_faces = 0;
            for (std::size_t f = 0; f < faces.size(); ++f) {
                const glm::dvec3 normal = f % 2 == 0 ? axes[f / 2] : -axes[f / 2];
                from_faces += faces[f].area * glm::dot(normal, faces[f].centroid - mean) / 3.0;
            }
            EXPECT_NEAR(from_faces, volume, 1e-9 * cube) << name << " trial " << trial;
            ++checked;
        }
    }
    EXPECT_EQ(checked, 1200u);
}

// The analytic gradient against central differences of the volume, rotating one axis at a time.
TEST(KdopPolytope, GradientMatchesFiniteDifferences) {
    Random random(7);
    std::vector<glm::dvec3> axes = builtin_axes("dop16-grass");
    std::vector<glm::dvec3> points;
    for (int i = 0; i < 9; ++i) points.emplace_back(random.uniform(), random.uniform(), random.uniform());
    std::vector<glm::dvec3> gradient(axes.size(), glm::dvec3(0.0)), sphere_gradient(axes.size(), glm::dvec3(0.0));
    KdopPolytope kdop(axes);
    kdop.volume_gradient(points, gradient);
    kdop.sphere_volume_gradient(sphere_gradient);
    std::vector<glm::dvec3> tripled(axes.size(), glm::dvec3(1.0));
    kdop.volume_gradient(points, tripled, 3);
    for (std::size_t i = 0; i < axes.size(); ++i)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(tripled[i][c], 1 + 3 * gradient[i][c], 1e-15) << "weight 3, added";
    for (std::size_t i = 0; i < axes.size(); ++i)
        for (int direction = 0; direction < 3; ++direction) {
            glm::dvec3 d(0.0);
            d[direction] = 1e-6;
            auto moved = [&](double sign) {
                std::vector<glm::dvec3> changed = axes;
                changed[i] = glm::normalize(axes[i]) + sign * d; // KdopPolytope normalizes again
                return KdopPolytope(changed);
            };
            // The derivative along d, less its part along the axis (which changes nothing).
            const glm::dvec3 a = glm::normalize(axes[i]);
            const double along = glm::dot(glm::dvec3(d - glm::dot(d, a) * a), gradient[i]);
            const double numeric = (moved(1).volume_of(points) - moved(-1).volume_of(points)) / 2.0;
            EXPECT_NEAR(along, numeric, 1e-6 * 1e-6 + 1e-4 * std::abs(numeric)) << "axis " << i << " dir " << direction;
            const double sphere_along = glm::dot(glm::dvec3(d - glm::dot(d, a) * a), sphere_gradient[i]);
            const double sphere_numeric = (sphere_volume(moved(1)) - sphere_volume(moved(-1))) / 2.0;
            EXPECT_NEAR(sphere_along, sphere_numeric, 1e-10 + 1e-4 * std::abs(sphere_numeric)) << "sphere axis " << i;
        }
}

} // namespace
} // namespace kdop
