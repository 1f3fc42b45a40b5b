// The ideal clip (the LP against the convex hull) and the volumes, on cases worked out by hand.
#include "accuracy/ideal_clip.h"
#include "accuracy/volume.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

namespace kdop {
namespace {

double exit_of(std::span<const glm::dvec3> n, glm::dvec3 current, glm::dvec3 history) {
    IdealClipper clipper;
    const std::optional<double> t = clipper.exit(n, current, history);
    EXPECT_TRUE(t.has_value());
    return t.value_or(NAN);
}

// The unit cube's eight corners and its center.
std::vector<glm::dvec3> cube() {
    std::vector<glm::dvec3> n;
    for (int i = 0; i < 8; ++i) n.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    n.emplace_back(0.5, 0.5, 0.5);
    return n;
}

TEST(IdealClip, CubeStopsAtTheFaceItCrosses) {
    const auto n = cube();
    const glm::dvec3 c(0.5, 0.5, 0.5);
    EXPECT_DOUBLE_EQ(exit_of(n, c, {2, 0.5, 0.5}), 1.0 / 3.0); // x = 1 at t = 0.5 / 1.5
    EXPECT_DOUBLE_EQ(exit_of(n, c, {0.5, -4.5, 0.5}), 0.1);    // y = 0 at t = 0.5 / 5
    EXPECT_DOUBLE_EQ(exit_of(n, c, {1.5, 1.5, 1.5}), 0.5);     // through the corner (1, 1, 1)
}

TEST(IdealClip, HistoryInsideTheHullIsKept) {
    const auto n = cube();
    EXPECT_EQ(exit_of(n, {0.5, 0.5, 0.5}, {0.9, 0.1, 0.3}), 1.0);
    EXPECT_EQ(exit_of(n, {0.5, 0.5, 0.5}, {1, 1, 0}), 1.0); // on a corner
    EXPECT_EQ(exit_of(n, {0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}), 1.0);
}

TEST(IdealClip, TetrahedronStopsAtTheSlantedFace) {
    // The corner tetrahedron x, y, z >= 0, x + y + z <= 1, where an AABB would keep (0.9, 0.9, 0.9).
    const std::vector<glm::dvec3> n = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.25, 0.25, 0.25}};
    const glm::dvec3 c(0.25, 0.25, 0.25);
    // From (0.25, 0.25, 0.25) toward (0.9, 0.9, 0.9): the sum 0.75 + 1.95 t reaches 1 at t = 0.25 / 1.95.
    EXPECT_NEAR(exit_of(n, c, {0.9, 0.9, 0.9}), 0.25 / 1.95, 1e-15);
    // Toward (-1, 0.25, 0.25): x = 0 at t = 0.2.
    EXPECT_NEAR(exit_of(n, c, {-1, 0.25, 0.25}), 0.2, 1e-15);
}

TEST(IdealClip, FlatSquareKeepsRaysInItsPlaneOnly) {
    // The square 0 <= x, y <= 1 at z = 0.5: a hull without volume.
    const std::vector<glm::dvec3> n = {{0, 0, 0.5}, {1, 0, 0.5}, {0, 1, 0.5}, {1, 1, 0.5}, {0.5, 0.5, 0.5}};
    const glm::dvec3 c(0.5, 0.5, 0.5);
    EXPECT_DOUBLE_EQ(exit_of(n, c, {2.5, 0.5, 0.5}), 0.25); // in the plane: stops at x = 1
    EXPECT_EQ(exit_of(n, c, {0.75, 0.25, 0.5}), 1.0);       // in the square: kept
    EXPECT_EQ(exit_of(n, c, {0.5, 0.5, 0.6}), 0.0);         // off the plane: nowhere to go
    EXPECT_EQ(exit_of(n, c, {0.75, 0.25, 0.5 + 1e-12}), 0.0);
}

TEST(IdealClip, SegmentKeepsOnlyItsOwnLine) {
    // A gray line from black to white, the current color a quarter of the way.
    const std::vector<glm::dvec3> n = {{0, 0, 0}, {1, 1, 1}, {0.25, 0.25, 0.25}};
    const glm::dvec3 c(0.25, 0.25, 0.25);
    EXPECT_DOUBLE_EQ(exit_of(n, c, {3.25, 3.25, 3.25}), 0.25); // along the line: stops at white
    EXPECT_EQ(exit_of(n, c, {0.5, 0.5, 0.5}), 1.0);
    EXPECT_EQ(exit_of(n, c, {0.5, 0.5, 0.4}), 0.0); // off the line
}

TEST(IdealClip, SinglePointKeepsNothingElse) {
    const std::vector<glm::dvec3> n(9, glm::dvec3(0.37, 0.37, 0.37));
    const glm::dvec3 c(0.37, 0.37, 0.37);
    EXPECT_EQ(exit_of(n, c, {0.37, 0.37, 0.3700001}), 0.0);
    EXPECT_EQ(exit_of(n, c, c), 1.0);
}

TEST(IdealClip, IsExactForHdrAndTinyColors) {
    // The cube scaled by 2^40 and by 2^-40: the same t, to the last bit.
    for (double scale : {0x1.0p40, 0x1.0p-40}) {
        std::vector<glm::dvec3> n = cube();
        for (glm::dvec3& p : n) p *= scale;
        EXPECT_EQ(exit_of(n, glm::dvec3(0.5) * scale, glm::dvec3(2, 0.5, 0.5) * scale), 1.0 / 3.0) << scale;
    }
}

TEST(IdealClip, ReportsACurrentColorOutsideTheHull) {
    IdealClipper clipper;
    const std::vector<glm::dvec3> n = {{0, 0, 0}, {1, 1, 1}};
    EXPECT_FALSE(clipper.exit(n, {1, 0, 0}, {2, 0, 0}).has_value());
}

TEST(IdealClip, AgreesWithTheAabbWhereTheHullIsTheBox) {
    // The neighborhood is the box's corners, so the hull is the box and the padding-free AABB exit
    // is the ideal one. 200 rays in random directions from an interior current color.
    const auto n = cube();
    const glm::dvec3 c(0.5, 0.5, 0.5);
    std::uint64_t state = 7;
    auto next = [&] {
        return double((state = state * 6364136223846793005ull + 1442695040888963407ull) >> 11) * 0x1.0p-53;
    };
    for (int i = 0; i < 200; ++i) {
        const glm::dvec3 h(next() * 4 - 1.5, next() * 4 - 1.5, next() * 4 - 1.5);
        double t = 1;
        for (int k = 0; k < 3; ++k) {
            const double d = h[k] - c[k];
            if (d > 0) t = std::min(t, (1 - c[k]) / d);
            if (d < 0) t = std::min(t, (0 - c[k]) / d);
        }
        EXPECT_NEAR(exit_of(n, c, h), t, 1e-15) << i;
    }
}

TEST(IdealExits, GathersTheNeighborhoodLikeTheShaders) {
    // A 3x1 image: black, gray, white. Every pixel's 3x3 neighborhood (clamped) spans black..white
    // only through the middle pixel, so at x = 1 a history along the gray line is kept up to white.
    Image current(3, 1), history(3, 1);
    current.at(0, 0) = {0, 0, 0, 1};
    current.at(1, 0) = {0.5f, 0.5f, 0.5f, 1};
    current.at(2, 0) = {1, 1, 1, 1};
    history = current;
    history.at(1, 0) = {2.5f, 2.5f, 2.5f, 1}; // from 0.5 toward 2.5: white at t = 0.25
    history.at(0, 0) = {0, 0, 1, 1};          // off the line: t = 0
    auto exits = ideal_exits(current, history, Neighborhood::n9);
    ASSERT_TRUE(exits) << exits.error().message;
    EXPECT_EQ((*exits)[0], 0.0);
    EXPECT_EQ((*exits)[1], 0.25);
    EXPECT_EQ((*exits)[2], 1.0);
}

TEST(Volume, HullOfTheCubeAndTheTetrahedron) {
    auto v = hull_volume(cube());
    ASSERT_TRUE(v) << v.error().message;
    EXPECT_NEAR(*v, 1.0, 1e-12);
    const std::vector<glm::dvec3> tetra = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.2, 0.2, 0.2}};
    v = hull_volume(tetra);
    ASSERT_TRUE(v) << v.error().message;
    EXPECT_NEAR(*v, 1.0 / 6.0, 1e-12);
}

TEST(Volume, DegenerateHullsHaveNone) {
    const std::vector<glm::dvec3> square = {{0, 0, 0.5}, {1, 0, 0.5}, {0, 1, 0.5}, {1, 1, 0.5}, {0.5, 0.5, 0.5}};
    const std::vector<glm::dvec3> segment = {{0, 0, 0}, {1, 1, 1}, {0.5, 0.5, 0.5}, {0.25, 0.25, 0.25}};
    const std::vector<glm::dvec3> point(9, glm::dvec3(0.37));
    const std::vector<glm::dvec3> tilted = {{0, 0, 0}, {1, 1, 0}, {0, 1, 1}, {1, 2, 1}, {0.5, 1, 0.5}}; // x - y + z = 0
    for (const auto* points : {&square, &segment, &point, &tilted}) {
        auto v = hull_volume(*points);
        ASSERT_TRUE(v) << v.error().message;
        EXPECT_EQ(*v, 0.0);
    }
}

TEST(Volume, SlabsOfABoxAndACutCorner) {
    const std::vector<ReferenceSlab> box = {{{1, 0, 0}, 0, 2}, {{0, 1, 0}, 0, 3}, {{0, 0, 1}, -1, 0}};
    auto v = slab_volume(box, {1, 1, -0.5});
    ASSERT_TRUE(v) << v.error().message;
    EXPECT_NEAR(*v, 6.0, 1e-12);
    // The unit cube cut by x + y + z <= 1 is the corner tetrahedron.
    std::vector<ReferenceSlab> cut = {{{1, 0, 0}, 0, 1}, {{0, 1, 0}, 0, 1}, {{0, 0, 1}, 0, 1}};
    cut.push_back({glm::normalize(glm::dvec3(1, 1, 1)), 0, 1 / std::sqrt(3.0)});
    v = slab_volume(cut, {0.2, 0.2, 0.2});
    ASSERT_TRUE(v) << v.error().message;
    EXPECT_NEAR(*v, 1.0 / 6.0, 1e-12);
}

TEST(Volume, UnboundedSlabsAreAnError) {
    const std::vector<ReferenceSlab> two = {{{1, 0, 0}, 0, 1}, {{0, 1, 0}, 0, 1}};
    EXPECT_FALSE(slab_volume(two, {0.5, 0.5, 0}));
}

} // namespace
} // namespace kdop
