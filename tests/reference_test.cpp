// The CPU reference itself, on cases small enough to work out by hand.
#include "reference/cpu_clip.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace kdop {
namespace {

const std::vector<glm::dvec3> kXyz = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
constexpr double e = kReferencePadding;

// Corners (0,0,0) and (1,1,1) of the unit cube, and the current color at its center.
const std::vector<glm::dvec3> kCube = {{0, 0, 0}, {1, 1, 1}, {0.5, 0.5, 0.5}};
const glm::dvec3 kCenter(0.5, 0.5, 0.5);

void expect_near(const glm::dvec3& a, const glm::dvec3& b) {
    EXPECT_NEAR(a.x, b.x, 1e-12);
    EXPECT_NEAR(a.y, b.y, 1e-12);
    EXPECT_NEAR(a.z, b.z, 1e-12);
}

TEST(Reference, AabbClipStopsAtThePaddedFace) {
    // Along +x from the center: leaves at x = 1 + e.
    expect_near(reference_clip(kXyz, kCube, kCenter, {2, 0.5, 0.5}, Mode::clip, 0), {1 + e, 0.5, 0.5});
    // Diagonal toward (2, 0.75, 0.5): x limits first, at t = (0.5 + e) / 1.5.
    double t = (0.5 + e) / 1.5;
    expect_near(reference_clip(kXyz, kCube, kCenter, {2, 0.75, 0.5}, Mode::clip, 0),
                kCenter + t * glm::dvec3(1.5, 0.25, 0));
}

TEST(Reference, HistoryInsideIsKept) {
    expect_near(reference_clip(kXyz, kCube, kCenter, {0.9, 0.1, 0.3}, Mode::clip, 0), {0.9, 0.1, 0.3});
}

TEST(Reference, ADiagonalAxisCutsTheBoxCorner) {
    // The neighborhood (0,0,0), (1,0,0), (0,1,0), (0,0,1) and the center of the first two: its hull
    // has x + y + z <= 1. With the (1,1,1) axis added, a history at (1,1,1) is clipped to that plane.
    const std::vector<glm::dvec3> n = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0, 0}};
    std::vector<glm::dvec3> axes = kXyz;
    axes.push_back(glm::normalize(glm::dvec3(1, 1, 1)));
    const glm::dvec3 current(0.5, 0, 0), history(1, 1, 1);
    // On the diagonal axis the slab's max is 1/sqrt(3) + e; current projects to 0.5/sqrt(3) and the
    // direction (0.5, 1, 1) to 2.5/sqrt(3). The Y axis allows t up to (1 + e) / 1, so the diagonal decides.
    double t = (1 / std::sqrt(3.0) + e - 0.5 / std::sqrt(3.0)) / (2.5 / std::sqrt(3.0));
    expect_near(reference_clip(axes, n, current, history, Mode::clip, 0), current + t * (history - current));
    // Without it, the box lets (1, 1, 1) through.
    expect_near(reference_clip(kXyz, n, current, history, Mode::clip, 0), {1, 1, 1});
}

TEST(Reference, ARayParallelToASlabIsNotLimitedByIt) {
    // A flat x channel (every x = 0.5) and a history with the same x: the x slab is [0.5 - e, 0.5 + e]
    // and the ray runs inside it, so y decides.
    const std::vector<glm::dvec3> n = {{0.5, 0, 0}, {0.5, 1, 1}, {0.5, 0.5, 0.5}};
    expect_near(reference_clip(kXyz, n, kCenter, {0.5, 3, 0.5}, Mode::clip, 0), {0.5, 1 + e, 0.5});
}

TEST(Reference, VarianceClipUsesMeanAndSigma) {
    // x values 0, 0, 3 (mean 1, population sigma sqrt(2)); y and z flat at 0. With gamma = 1 the x
    // slab is [1 - sqrt(2), 1 + sqrt(2)] widened to contain current (x = 0) and padded.
    const std::vector<glm::dvec3> n = {{0, 0, 0}, {0, 0, 0}, {3, 0, 0}};
    glm::dvec3 out = reference_clip(kXyz, n, {0, 0, 0}, {10, 0, 0}, Mode::varclip, 1.0);
    expect_near(out, {1 + std::sqrt(2.0) + e, 0, 0});
    out = reference_clip(kXyz, n, {0, 0, 0}, {10, 0, 0}, Mode::varclip, 0.5);
    expect_near(out, {1 + 0.5 * std::sqrt(2.0) + e, 0, 0});
}

TEST(Reference, NeighborhoodShapes) {
    EXPECT_EQ(reference_offsets(Neighborhood::n9).size(), 9u);
    auto plus = reference_offsets(Neighborhood::n5);
    ASSERT_EQ(plus.size(), 5u);
    for (glm::ivec2 o : plus) EXPECT_TRUE(o.x == 0 || o.y == 0);
}

} // namespace
} // namespace kdop
