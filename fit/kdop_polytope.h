// The k-DOP of a set of slabs as a polytope: its exact volume, and each face's area and centroid,
// which give the volume's gradient with respect to the axes (fit/axis_fit.h). The fitting
// objective evaluates this for every neighborhood of a scene, many times, so it is written for
// speed: no allocation, a polytope clipped slab by slab from the parallelepiped of three of them,
// each vertex knowing its three neighbors (a clip measures each vertex's distance to its plane,
// then edits only the edges it cuts), each face measured from its edges in one pass at the end.
// Where data decides (which point sets a slab's bound, which vertices lie outside a plane) it
// selects instead of branching: such branches mispredict about half the time, and removing them
// made the fit 1.3x faster for 7% more instructions (cachegrind's branch simulation: 41% fewer
// mispredictions). So count instructions and mispredictions, not instructions alone, here.
//
// Why not Qhull (accuracy/volume.h, which the tests check this against): a half-space
// intersection through Qhull costs tens of microseconds; with 8 axes this costs about 12,000
// instructions (callgrind), volume and gradient, about a microsecond.
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace kdop {

// Axis sets of up to this many axes (the paper's largest has 16).
inline constexpr std::size_t kMaxPolytopeAxes = 32;

class KdopPolytope {
public:
    // `axes` need not be unit length, but must span three dimensions (the k-DOP is bounded).
    explicit KdopPolytope(std::span<const glm::dvec3> axes);

    std::size_t axis_count() const { return axes_.size(); }
    const std::vector<glm::dvec3>& unit_axes() const { return axes_; }

    // A face of the k-DOP: the part of a slab's plane on its boundary (area 0 if the plane does not
    // touch it). Face 2i lies on the plane x . a_i = hi_i, face 2i+1 on x . a_i = lo_i (unit a_i).
    struct Face {
        double area = 0;
        glm::dvec3 centroid{0.0};
    };

    // The volume of { x : lo_i <= x . a_i <= hi_i for every unit axis a_i }, and, when `faces` has
    // 2 x axis_count() entries, every face. Needs lo_i <= hi_i; a slab of no width gives volume 0.
    double volume(std::span<const double> lo, std::span<const double> hi, std::span<Face> faces = {}) const;

    // The same for the k-DOP of `points`: each slab spans their projections.
    double volume_of(std::span<const glm::dvec3> points, std::span<Face> faces = {}) const;

    // The volume of the k-DOP of `points`, adding its gradient with respect to each unit axis,
    // times `weight`, to `gradient` (axis_count() entries). Moving axis a by da moves its high plane outward by
    // da . (p_hi - x) at a point x of the face (p_hi: the point of largest projection, which sets
    // the bound) and its low plane by da . (x - p_lo); over the faces that is
    //   dV/da = A_hi (p_hi - c_hi) + A_lo (c_lo - p_lo)
    // with A and c a face's area and centroid. It is perpendicular to a, as scaling an axis changes
    // no slab. NaN (and no gradient added) where the polytope could not be built.
    double volume_gradient(std::span<const glm::dvec3> points, std::span<glm::dvec3> gradient, double weight = 1) const;

    // The k-DOP around the unit sphere: every slab [-1, 1].
    double sphere_volume(std::span<Face> faces = {}) const;

    // Its volume and gradient, as volume_gradient; the sphere's support point in
    // direction a is a itself: dV/da = A_hi (a - c_hi) + A_lo (c_lo + a).
    double sphere_volume_gradient(std::span<glm::dvec3> gradient) const;

private:
    // Each slab's bounds over `points`, and which point sets each.
    struct SlabBounds {
        double lo[kMaxPolytopeAxes], hi[kMaxPolytopeAxes], first[kMaxPolytopeAxes]; // first: of points[0]
        std::size_t lowest[kMaxPolytopeAxes], highest[kMaxPolytopeAxes];
    };
    SlabBounds bounds_of(std::span<const glm::dvec3> points) const;

    // The volume of the k-DOP whose slabs are [lo_i, hi_i] in coordinates centered on a point
    // (lo and hi relative to it), and its 2 x axis_count() faces (area 0 for a face it lacks),
    // relative to that point. `size` is the scale of the absolute coordinates, for the tolerance.
    struct LocalFace { // as Face, left uninitialized: solve fills it
        double area;
        glm::dvec3 centroid;
    };
    double solve(const double* lo, const double* hi, double size, LocalFace* faces) const;

    std::vector<glm::dvec3> axes_;      // unit
    std::array<std::size_t, 3> base_{}; // the axes whose slabs make the starting parallelepiped
    glm::dmat3 base_inverse_{1.0};      // rows a_base -> the point with given projections
    // The parallelepiped's vertex b (bit k set: on the high plane of base axis k): its neighbors,
    // counter-clockwise seen from outside, and the plane of the face left of each edge to them.
    int base_neighbors_[8][3] = {};
    int base_faces_[8][3] = {};
    // Each plane's face is measured in its projection on the coordinate plane (x, y), where z is
    // the largest component of its normal n (by size) and x, y, z are in cyclic order.
    struct Projection {
        int x, y, z;
        double nx, ny, half_over_nz; // n_x, n_y, 1 / (2 n_z)
    };
    Projection planes_[2 * kMaxPolytopeAxes] = {};
};

} // namespace kdop
