#include "fit/kdop_polytope.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace kdop {
namespace {

constexpr int kMaxPlanes = 2 * static_cast<int>(kMaxPolytopeAxes);
// Room for a simple polytope of every plane (2F - 4 vertices) and the vertices a clip adds before
// it drops those cut away.
constexpr int kMaxVertices = 4 * kMaxPlanes;

// A convex polytope in which every vertex joins three edges (r3d's representation: Powell and
// Abel, "An exact general remeshing scheme applied to physically conservative voxelization", 2015).
// A vertex knows its three neighbors, counter-clockwise seen from outside, and the plane of the face
// left of the edge to each (seen from outside): the face between neighbors k and k + 1. A plane
// through a vertex leaves an edge of no length instead of a vertex of four edges, so clipping never
// meets a case it cannot represent, and the faces need no loops: each directed edge lies on the face
// left of it.
struct Polytope {
    double coord[3][kMaxVertices]; // x, y, z of each vertex
    int neighbor[kMaxVertices][3];
    int face[kMaxVertices][3];
    int count = 0;

    // Where `from` lists `to` (the first time, if twice).
    int index_of(int from, int to) const { return neighbor[from][0] == to ? 0 : neighbor[from][1] == to ? 1 : 2; }
    // Moves vertex `from` to the free slot `to`, and its neighbors' links with it.
    void move(int from, int to) {
        for (int c = 0; c < 3; ++c) coord[c][to] = coord[c][from];
        for (int k = 0; k < 3; ++k) {
            const int n = neighbor[to][k] = neighbor[from][k];
            face[to][k] = face[from][k];
            neighbor[n][index_of(n, from)] = to;
        }
    }
};

// Scratch space for clipping, kept across the clips of one polytope: per plane, the new vertex
// whose left face it is, in the clip `stamp` (the high bits).
struct ClipScratch {
    int left_of[kMaxPlanes];
    int stamp = 0;
};

enum class Clip { unchanged, clipped, empty, failed };

// Keeps the part of `poly` where side(v) <= tolerance, the new face on plane `plane`: `side` holds
// each vertex's signed distance to the plane (positive outside), `outside` the vertices where it
// is above the tolerance, in order. A vertex within the tolerance counts as on the plane (inside),
// so a face nearly in it is kept whole instead of cut into slivers. Each new vertex's entry in
// `next_side` is set to `new_side`; `moved` says whether other vertices changed slots.
Clip cut(Polytope& poly, int plane, const double* side, const int* outside, int outside_count, double tolerance,
         ClipScratch& scratch, double* next_side, double new_side, bool& moved) {
    const int old = poly.count;
    moved = false;
    if (outside_count == 0) return Clip::unchanged;
    if (outside_count == old) return Clip::empty;
    if (old + 3 * outside_count > kMaxVertices) return Clip::failed;
    constexpr int kVertexBits = 0xffff;
    const int stamp = (scratch.stamp += kVertexBits + 1);

    // A new vertex where each edge from inside to outside crosses the plane, in the outside one's
    // place among the inside one's neighbors; the first from each outside vertex takes its slot.
    // Seen from outside, its neighbors are the inside one, then the new vertices on the face right
    // of that edge and on the face left of it; its faces, the right one, the new one, the left one.
    // Each face the plane cuts has one new vertex where its boundary leaves the kept part (whose
    // left face it is) and one where it comes back; a face with two of either has been scrambled
    // by rounding.
    int count = old;
    int created[kMaxVertices], created_count = 0;
    int holes[kMaxVertices]; // outside vertices with no inside neighbor, in order
    int hole_count = 0;
    for (int i = 0; i < outside_count; ++i) {
        const int u = outside[i];
        const double pu[3] = {poly.coord[0][u], poly.coord[1][u], poly.coord[2][u]};
        const int neighbors[3] = {poly.neighbor[u][0], poly.neighbor[u][1], poly.neighbor[u][2]};
        const int faces[3] = {poly.face[u][0], poly.face[u][1], poly.face[u][2]};
        int w = u;
        for (int k = 0; k < 3; ++k) {
            const int v = neighbors[k];
            if (side[v] > tolerance) continue;
            if (w != u) {
                w = count++;
                poly.neighbor[v][poly.index_of(v, u)] = w;
            }
            // v is within the tolerance, perhaps just beyond the plane: then the crossing is v.
            const double t = std::max(side[v] / (side[v] - side[u]), 0.0);
            const double pv[3] = {poly.coord[0][v], poly.coord[1][v], poly.coord[2][v]};
            for (int c = 0; c < 3; ++c) poly.coord[c][w] = pv[c] + t * (pu[c] - pv[c]);
            next_side[w] = new_side;
            // The face left of v -> u is right of u -> v: u's face k + 2.
            const int left = faces[(k + 2) % 3];
            poly.neighbor[w][0] = v;
            poly.face[w][0] = faces[k];
            poly.face[w][1] = plane;
            poly.face[w][2] = left;
            if ((scratch.left_of[left] & ~kVertexBits) == stamp) return Clip::failed;
            scratch.left_of[left] = stamp | w;
            created[created_count++] = w;
            w = -1;
        }
        if (w == u) holes[hole_count++] = u;
    }
    // w's neighbor across its right face is the new vertex whose left face that is.
    for (int i = 0; i < created_count; ++i) {
        const int w = created[i], x = scratch.left_of[poly.face[w][0]];
        if ((x & ~kVertexBits) != stamp) return Clip::failed;
        poly.neighbor[w][1] = x & kVertexBits;
        poly.neighbor[x & kVertexBits][2] = w;
    }
    // Fill the holes from the top.
    for (int low = 0, high = hole_count - 1; low <= high;) {
        if (holes[high] == count - 1) {
            --count;
            --high;
        } else {
            poly.move(--count, holes[low++]);
            moved = true;
        }
    }
    poly.count = count;
    return Clip::clipped;
}

// Starts `poly` as the parallelepiped of the base slabs: vertex b (bit k set: on the high plane of
// base axis k) at the sum of corner[k][bit k], linked as `neighbors` and `faces` say.
void start_parallelepiped(Polytope& poly, const glm::dvec3 (&corner)[3][2], const int (&neighbors)[8][3],
                          const int (&faces)[8][3]) {
    for (int b = 0; b < 8; ++b) {
        const glm::dvec3 p = corner[0][b & 1] + corner[1][b >> 1 & 1] + corner[2][b >> 2 & 1];
        for (int c = 0; c < 3; ++c) poly.coord[c][b] = p[c];
        for (int k = 0; k < 3; ++k) {
            poly.neighbor[b][k] = neighbors[b][k];
            poly.face[b][k] = faces[b][k];
        }
    }
    poly.count = 8;
}

// Clips `poly` to the slab lo <= x . a <= hi of axis `axis`, high plane then low (faces 2 axis and
// 2 axis + 1): unchanged or clipped, or why not. Distances within `tolerance` count as 0. One
// projection serves both planes: the low one's outside vertices are found before the high one is
// cut (which moves none of them unless it fills holes), and the vertices that cut adds lie on the
// high plane.
Clip clip_slab(Polytope& poly, int axis, glm::dvec3 a, double lo, double hi, double tolerance, ClipScratch& scratch) {
    double side_hi[kMaxVertices], side_lo[kMaxVertices];
    int outside_hi[kMaxVertices], outside_lo[kMaxVertices];
    auto project = [&] {
        const int count = poly.count;
        const double *x = poly.coord[0], *y = poly.coord[1], *z = poly.coord[2];
        for (int v = 0; v < count; ++v) {
            const double q = a.x * x[v] + a.y * y[v] + a.z * z[v];
            side_hi[v] = q - hi;
            side_lo[v] = lo - q;
        }
    };
    project();
    // Lists written without branches (each slot written, kept by the count), as in bounds_of.
    int hi_count = 0, lo_count = 0;
    for (int v = 0; v < poly.count; ++v) {
        outside_hi[hi_count] = v;
        hi_count += side_hi[v] > tolerance;
        outside_lo[lo_count] = v;
        lo_count += side_lo[v] > tolerance;
    }
    // The high plane, then the low one.
    for (int high = 1; high >= 0; --high) {
        bool moved = false;
        const Clip clipped =
            cut(poly, 2 * axis + (high ? 0 : 1), high ? side_hi : side_lo, high ? outside_hi : outside_lo,
                high ? hi_count : lo_count, tolerance, scratch, high ? side_lo : side_hi, high ? lo - hi : 0, moved);
        if (clipped == Clip::empty || clipped == Clip::failed) return clipped;
        if (clipped == Clip::clipped && high && moved) { // the low plane's outside vertices, again
            project();
            lo_count = 0;
            for (int v = 0; v < poly.count; ++v) {
                outside_lo[lo_count] = v;
                lo_count += side_lo[v] > tolerance;
            }
        }
    }
    return Clip::clipped;
}

} // namespace

KdopPolytope::KdopPolytope(std::span<const glm::dvec3> axes) {
    if (axes.size() < 3 || axes.size() > kMaxPolytopeAxes) throw std::invalid_argument("KdopPolytope: 3 to 32 axes");
    for (const glm::dvec3& a : axes) axes_.push_back(glm::normalize(a));
    // The starting parallelepiped: the three slabs furthest from parallel, so it is well shaped.
    double best = 0;
    for (std::size_t i = 0; i < axes_.size(); ++i)
        for (std::size_t j = i + 1; j < axes_.size(); ++j)
            for (std::size_t k = j + 1; k < axes_.size(); ++k) {
                const double det = std::abs(glm::determinant(glm::dmat3(axes_[i], axes_[j], axes_[k])));
                if (det > best) {
                    best = det;
                    base_ = {i, j, k};
                }
            }
    if (best < 1e-9) throw std::invalid_argument("KdopPolytope: the axes do not span three dimensions");
    // Rows a_i: M x = projections; glm's matrices are column-major, so the transpose of the columns.
    const glm::dmat3 m = glm::transpose(glm::dmat3(axes_[base_[0]], axes_[base_[1]], axes_[base_[2]]));
    base_inverse_ = glm::inverse(m);
    // Vertex b's edges run along column k of the inverse, forward where bit k is clear. Its
    // neighbors are counter-clockwise from outside when the edges make a left-handed frame (at the
    // corner of the positive octant, -x, -y, -z do); the face between neighbors k and k + 1 is the
    // third base axis's, on b's side of it.
    for (int b = 0; b < 8; ++b) {
        int bits[3] = {0, 1, 2};
        glm::dmat3 edges;
        for (int k = 0; k < 3; ++k) edges[k] = (b >> k & 1 ? -1.0 : 1.0) * base_inverse_[k];
        if (glm::determinant(edges) > 0) std::swap(bits[1], bits[2]);
        for (int k = 0; k < 3; ++k) {
            const int third = 3 - bits[k] - bits[(k + 1) % 3];
            base_neighbors_[b][k] = b ^ (1 << bits[k]);
            base_faces_[b][k] = 2 * static_cast<int>(base_[third]) + (b >> third & 1 ? 0 : 1);
        }
    }
    for (std::size_t f = 0; f < 2 * axes_.size(); ++f) {
        const glm::dvec3 normal = f % 2 == 0 ? axes_[f / 2] : -axes_[f / 2];
        const glm::dvec3 size = glm::abs(normal);
        Projection& p = planes_[f];
        p.z = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
        p.x = (p.z + 1) % 3;
        p.y = (p.z + 2) % 3;
        p.nx = normal[p.x];
        p.ny = normal[p.y];
        p.half_over_nz = 0.5 / normal[p.z];
    }
}

KdopPolytope::SlabBounds KdopPolytope::bounds_of(std::span<const glm::dvec3> points) const {
    // Selects instead of branches, in registers: which point sets a bound is data-dependent, so
    // branches mispredict; this loop took a quarter of the fitting time with them.
    SlabBounds b;
    for (std::size_t i = 0; i < axes_.size(); ++i) {
        const glm::dvec3 a = axes_[i];
        const double first = glm::dot(a, points[0]);
        double lo = first, hi = first;
        std::size_t lowest = 0, highest = 0;
        for (std::size_t j = 1; j < points.size(); ++j) {
            const double q = glm::dot(a, points[j]);
            lowest = q < lo ? j : lowest;
            lo = q < lo ? q : lo;
            highest = q > hi ? j : highest;
            hi = q > hi ? q : hi;
        }
        b.first[i] = first;
        b.lo[i] = lo;
        b.hi[i] = hi;
        b.lowest[i] = lowest;
        b.highest[i] = highest;
    }
    return b;
}

double KdopPolytope::volume_of(std::span<const glm::dvec3> points, std::span<Face> faces) const {
    const SlabBounds b = bounds_of(points);
    return volume({b.lo, axes_.size()}, {b.hi, axes_.size()}, faces);
}

double KdopPolytope::volume_gradient(std::span<const glm::dvec3> points, std::span<glm::dvec3> gradient,
                                     double weight) const {
    const std::size_t n = axes_.size();
    const SlabBounds b = bounds_of(points);
    // Coordinates centered on the first point, which the k-DOP contains.
    double lo[kMaxPolytopeAxes], hi[kMaxPolytopeAxes], size = 0;
    for (std::size_t i = 0; i < n; ++i) {
        size = std::max(size, std::max(std::abs(b.lo[i]), std::abs(b.hi[i])));
        lo[i] = b.lo[i] - b.first[i];
        hi[i] = b.hi[i] - b.first[i];
    }
    LocalFace faces[2 * kMaxPolytopeAxes];
    const double v = solve(lo, hi, size, faces);
    if (std::isnan(v)) return v;
    const glm::dvec3 origin = points[0];
    for (std::size_t i = 0; i < n; ++i)
        gradient[i] += weight * (faces[2 * i].area * (points[b.highest[i]] - origin - faces[2 * i].centroid) +
                                 faces[2 * i + 1].area * (faces[2 * i + 1].centroid - (points[b.lowest[i]] - origin)));
    return v;
}

double KdopPolytope::sphere_volume(std::span<Face> faces) const {
    const std::vector<double> lo(axes_.size(), -1.0), hi(axes_.size(), 1.0);
    return volume(lo, hi, faces);
}

double KdopPolytope::sphere_volume_gradient(std::span<glm::dvec3> gradient) const {
    const std::size_t n = axes_.size();
    Face faces[2 * kMaxPolytopeAxes];
    const double v = sphere_volume({faces, 2 * n});
    if (std::isnan(v)) return v;
    for (std::size_t i = 0; i < n; ++i)
        gradient[i] += faces[2 * i].area * (axes_[i] - faces[2 * i].centroid) +
                       faces[2 * i + 1].area * (faces[2 * i + 1].centroid + axes_[i]);
    return v;
}

double KdopPolytope::volume(std::span<const double> lo, std::span<const double> hi, std::span<Face> faces) const {
    const std::size_t n = axes_.size();
    const bool want_faces = faces.size() == 2 * n;
    // Coordinates centered on the starting parallelepiped.
    const glm::dvec3 origin = base_inverse_ * (0.5 * (glm::dvec3(hi[base_[0]], hi[base_[1]], hi[base_[2]]) +
                                                      glm::dvec3(lo[base_[0]], lo[base_[1]], lo[base_[2]])));
    double local_lo[kMaxPolytopeAxes], local_hi[kMaxPolytopeAxes], size = 0;
    for (std::size_t i = 0; i < n; ++i) {
        size = std::max({size, std::abs(lo[i]), std::abs(hi[i])});
        const double at = glm::dot(axes_[i], origin);
        local_lo[i] = lo[i] - at;
        local_hi[i] = hi[i] - at;
    }
    LocalFace local[2 * kMaxPolytopeAxes];
    const double v = solve(local_lo, local_hi, size, local);
    if (want_faces)
        for (std::size_t f = 0; f < 2 * n; ++f)
            faces[f] = local[f].area > 0 ? Face{local[f].area, local[f].centroid + origin} : Face{};
    return v;
}

double KdopPolytope::solve(const double* lo, const double* hi, double size, LocalFace* faces) const {
    const std::size_t n = axes_.size();
    for (std::size_t i = 0; i < n; ++i)
        if (!(hi[i] > lo[i])) { // no width (or NaN): a flat k-DOP
            std::fill_n(faces, 2 * n, LocalFace{0, glm::dvec3(0.0)});
            return 0.0;
        }

    // The parallelepiped of the base slabs, then the rest of the slabs. Distances within 1e-12 of
    // the coordinates' size count as 0.
    Polytope poly;
    glm::dvec3 corner[3][2]; // base axis k's contribution at its low and high plane
    for (int k = 0; k < 3; ++k) {
        corner[k][0] = lo[base_[k]] * base_inverse_[k];
        corner[k][1] = hi[base_[k]] * base_inverse_[k];
    }
    start_parallelepiped(poly, corner, base_neighbors_, base_faces_);
    const double tolerance = 1e-12 * size;
    ClipScratch scratch;
    std::fill_n(scratch.left_of, 2 * n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        if (i == base_[0] || i == base_[1] || i == base_[2]) continue;
        switch (clip_slab(poly, static_cast<int>(i), axes_[i], lo[i], hi[i], tolerance, scratch)) {
        case Clip::unchanged:
        case Clip::clipped: break;
        case Clip::empty: // cannot happen for slabs around one set of points
            std::fill_n(faces, 2 * n, LocalFace{0, glm::dvec3(0.0)});
            return 0.0;
        case Clip::failed: return std::numeric_limits<double>::quiet_NaN();
        }
    }

    // Each face's area and centroid from its projection on the coordinate plane (x, y) across the
    // axis's largest component z: twice the projected area is the sum over its edges a -> b of
    // x_a y_b - x_b y_a, and the projected centroid weights (x_a + x_b, y_a + y_b) by the same terms.
    // Each directed edge lies on the face left of it.
    struct Sums {
        double twice_area, x, y;
    };
    Sums sums[2 * kMaxPolytopeAxes];
    const double* along_x[2 * kMaxPolytopeAxes];
    const double* along_y[2 * kMaxPolytopeAxes];
    for (std::size_t f = 0; f < 2 * n; ++f) {
        sums[f] = {0, 0, 0};
        along_x[f] = poly.coord[planes_[f].x];
        along_y[f] = poly.coord[planes_[f].y];
    }
    for (int v = 0; v < poly.count; ++v)
        for (int k = 0; k < 3; ++k) {
            const int f = poly.face[v][k], w = poly.neighbor[v][k];
            const double* x = along_x[f];
            const double* y = along_y[f];
            const double xa = x[v], ya = y[v], xb = x[w], yb = y[w];
            const double cross = xa * yb - xb * ya;
            sums[f].twice_area += cross;
            sums[f].x += cross * (xa + xb);
            sums[f].y += cross * (ya + yb);
        }
    // The projection scales areas by n_z; the centroid lies on the plane n . c = offset. The volume
    // is the sum over faces of area x offset / 3 (the divergence theorem, from the origin).
    double volume = 0;
    for (std::size_t f = 0; f < 2 * n; ++f) {
        const Sums& s = sums[f];
        const Projection& p = planes_[f];
        const double area = s.twice_area * p.half_over_nz;
        if (!(area > 0)) {
            faces[f] = {0, glm::dvec3(0.0)};
            continue;
        }
        const double offset = f % 2 == 0 ? hi[f / 2] : -lo[f / 2];
        double centroid[3];
        centroid[p.x] = s.x / (3 * s.twice_area);
        centroid[p.y] = s.y / (3 * s.twice_area);
        centroid[p.z] = (offset - p.nx * centroid[p.x] - p.ny * centroid[p.y]) * (2 * p.half_over_nz);
        faces[f] = {area, glm::dvec3(centroid[0], centroid[1], centroid[2])};
        volume += area * offset / 3;
    }
    return std::max(volume, 0.0);
}

} // namespace kdop
