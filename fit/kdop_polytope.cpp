#include "kdop_polytope.h"

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
// A face is bounded by at most every other plane; a simple polytope with F faces has at most
// 2F - 4 vertices, and a clip adds at most one per face before it frees those cut away.
constexpr int kMaxFaceSize = kMaxPlanes;
constexpr int kMaxVertices = 4 * kMaxPlanes;

// A convex polytope as faces, each a loop of vertex slots, counter-clockwise seen from outside.
// Clipping edits it in place: a face the plane misses is not touched, vertices keep their slots,
// and the slots of vertices cut away are reused.
struct Polytope {
    glm::dvec3 vertices[kMaxVertices];
    int live[kMaxVertices]; // the slots in use
    int live_count = 0;
    int free_slots[kMaxVertices];
    int free_count = 0;
    int slot_count = 0; // slots ever used
    struct Face {
        int plane; // 2i: x . a_i <= hi_i, 2i+1: x . a_i >= lo_i
        int size;
        int loop[kMaxFaceSize];
    };
    Face faces[kMaxPlanes];
    int face_count = 0;

    int new_vertex(const glm::dvec3& p) {
        const int slot = free_count ? free_slots[--free_count] : slot_count++;
        vertices[slot] = p;
        return slot;
    }
};

enum class Clip { unchanged, clipped, empty, failed };

// Keeps the part of `poly` where n . x <= d, adding the new face on plane `plane`. A vertex within
// `tolerance` of the plane counts as on it (inside), so a face nearly in the plane is kept whole
// instead of cut into slivers whose order rounding could scramble.
Clip clip(Polytope& poly, int plane, const glm::dvec3& n, double d, double tolerance) {
    double side[kMaxVertices];
    bool is_outside[kMaxVertices];
    int outside_total = 0;
    for (int k = 0; k < poly.live_count; ++k) {
        const int v = poly.live[k];
        side[v] = glm::dot(n, poly.vertices[v]) - d;
        is_outside[v] = side[v] > tolerance;
        outside_total += is_outside[v];
    }
    if (outside_total == 0) return Clip::unchanged;
    if (outside_total == poly.live_count) return Clip::empty;
    auto outside = [&](int v) { return is_outside[v]; };

    struct Cut {
        int inside, outside, vertex;
    };
    Cut cuts[kMaxPlanes];
    int cut_count = 0;
    int cap_next[kMaxVertices]; // a new vertex -> the next one around the new face
    // The point where edge inside-outside meets the plane, made once for both faces of the edge.
    auto cut = [&](int inside, int out) {
        for (int c = 0; c < cut_count; ++c)
            if (cuts[c].inside == inside && cuts[c].outside == out) return cuts[c].vertex;
        if (cut_count == kMaxPlanes) return -1;
        const double t = side[inside] / (side[inside] - side[out]);
        const int v = poly.new_vertex(poly.vertices[inside] + t * (poly.vertices[out] - poly.vertices[inside]));
        cap_next[v] = -1;
        cuts[cut_count++] = {inside, out, v};
        return v;
    };

    int kept_faces = 0;
    for (int f = 0; f < poly.face_count; ++f) {
        Polytope::Face& face = poly.faces[f];
        int outside_count = 0;
        for (int k = 0; k < face.size; ++k) outside_count += outside(face.loop[k]);
        if (outside_count == 0) { // untouched; moved down over faces cut away, its loop only
            if (kept_faces != f) {
                Polytope::Face& to = poly.faces[kept_faces];
                to.plane = face.plane;
                to.size = face.size;
                std::copy_n(face.loop, face.size, to.loop);
            }
            ++kept_faces;
            continue;
        }
        if (outside_count == face.size) continue; // cut away whole
        int loop[kMaxFaceSize + 2];
        int size = 0, exit = -1, entry = -1, exits = 0;
        for (int k = 0, u = face.loop[face.size - 1]; k < face.size; ++k) {
            const int w = face.loop[k];
            // Edge u -> w: keep u's side of it, and where it crosses, the crossing.
            if (!outside(u) && outside(w)) {
                exit = cut(u, w);
                loop[size++] = exit;
                ++exits;
            } else if (outside(u) && !outside(w)) {
                entry = cut(w, u);
                loop[size++] = entry;
            }
            if (!outside(w)) loop[size++] = w;
            u = w;
        }
        // Only a convex face crosses the plane once each way; more means rounding scrambled it.
        if (exits != 1 || exit < 0 || entry < 0 || size > kMaxFaceSize) return Clip::failed;
        // This face runs exit -> entry along the plane; the new face, its neighbor there, runs back.
        cap_next[entry] = exit;
        if (size < 3) continue; // a sliver of no area
        Polytope::Face& kept = poly.faces[kept_faces++];
        kept.plane = face.plane;
        kept.size = size;
        std::copy_n(loop, size, kept.loop);
    }
    poly.face_count = kept_faces;

    // The new face: follow the links from any point where an edge was cut.
    Polytope::Face& cap = poly.faces[poly.face_count];
    cap.plane = plane;
    cap.size = 0;
    const int first = cuts[0].vertex;
    int v = first;
    do {
        if (v < 0 || cap.size == cut_count) return Clip::failed;
        cap.loop[cap.size++] = v;
        v = cap_next[v];
    } while (v != first);
    if (cap.size >= 3) ++poly.face_count;

    // The vertices now: those inside, and the new ones; the slots of the rest are free again.
    int live_count = 0;
    for (int k = 0; k < poly.live_count; ++k) {
        const int u = poly.live[k];
        if (is_outside[u])
            poly.free_slots[poly.free_count++] = u;
        else
            poly.live[live_count++] = u;
    }
    for (int c = 0; c < cut_count; ++c) poly.live[live_count++] = cuts[c].vertex;
    poly.live_count = live_count;
    return Clip::clipped;
}

} // namespace

KdopPolytope::KdopPolytope(std::span<const glm::dvec3> axes) {
    if (axes.size() < 3 || axes.size() > kMaxPolytopeAxes)
        throw std::invalid_argument("KdopPolytope: 3 to 32 axes");
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
    base_flipped_ = glm::determinant(m) < 0;
}

KdopPolytope::SlabBounds KdopPolytope::bounds_of(std::span<const glm::dvec3> points) const {
    SlabBounds b;
    for (std::size_t i = 0; i < axes_.size(); ++i) {
        b.lo[i] = b.hi[i] = glm::dot(axes_[i], points[0]);
        b.lowest[i] = b.highest[i] = 0;
        for (std::size_t j = 1; j < points.size(); ++j) {
            const double q = glm::dot(axes_[i], points[j]);
            if (q < b.lo[i]) b.lo[i] = q, b.lowest[i] = j;
            if (q > b.hi[i]) b.hi[i] = q, b.highest[i] = j;
        }
    }
    return b;
}

double KdopPolytope::volume_of(std::span<const glm::dvec3> points, std::span<Face> faces) const {
    const SlabBounds b = bounds_of(points);
    return volume({b.lo, axes_.size()}, {b.hi, axes_.size()}, faces);
}

double KdopPolytope::volume_gradient(std::span<const glm::dvec3> points, std::span<glm::dvec3> gradient) const {
    const std::size_t n = axes_.size();
    const SlabBounds b = bounds_of(points);
    Face faces[2 * kMaxPolytopeAxes];
    const double v = volume({b.lo, n}, {b.hi, n}, {faces, 2 * n});
    if (std::isnan(v)) return v;
    for (std::size_t i = 0; i < n; ++i)
        gradient[i] += faces[2 * i].area * (points[b.highest[i]] - faces[2 * i].centroid) +
                       faces[2 * i + 1].area * (faces[2 * i + 1].centroid - points[b.lowest[i]]);
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
    if (want_faces) std::fill(faces.begin(), faces.end(), Face{});
    for (std::size_t i = 0; i < n; ++i)
        if (!(hi[i] > lo[i])) return 0.0; // no width (or NaN): a flat k-DOP

    // The parallelepiped of the base slabs: vertex b (bit k set: hi of base axis k).
    Polytope poly;
    for (int b = 0; b < 8; ++b) {
        glm::dvec3 q;
        for (int k = 0; k < 3; ++k) q[k] = (b >> k & 1) ? hi[base_[k]] : lo[base_[k]];
        poly.live[poly.live_count++] = poly.new_vertex(base_inverse_ * q);
    }
    // Face (k, high): the vertices with bit k equal to `high`, around the other two bits. The cycle
    // 00 -> 01 -> 11 -> 10 of bits (k+1, k+2) is counter-clockwise from outside on the high face of
    // a right-handed frame; low faces and a left-handed (flipped) frame run it backwards.
    for (int k = 0; k < 3; ++k)
        for (int high = 0; high < 2; ++high) {
            const int bit1 = 1 << ((k + 1) % 3), bit2 = 1 << ((k + 2) % 3), fixed = high ? 1 << k : 0;
            int cycle[4] = {fixed, fixed | bit1, fixed | bit1 | bit2, fixed | bit2};
            if (!high != base_flipped_) std::swap(cycle[1], cycle[3]);
            Polytope::Face& face = poly.faces[poly.face_count++];
            face.plane = 2 * static_cast<int>(base_[k]) + (high ? 0 : 1);
            face.size = 4;
            std::copy_n(cycle, 4, face.loop);
        }

    // The rest of the slabs, plane by plane. Distances within 1e-12 of the polytope's size count as 0.
    double size = 0;
    for (std::size_t i = 0; i < n; ++i) size = std::max({size, std::abs(lo[i]), std::abs(hi[i])});
    const double tolerance = 1e-12 * size;
    for (std::size_t i = 0; i < n; ++i) {
        if (i == base_[0] || i == base_[1] || i == base_[2]) continue;
        for (int high = 1; high >= 0; --high) {
            const glm::dvec3 normal = high ? axes_[i] : -axes_[i];
            const double offset = high ? hi[i] : -lo[i];
            switch (clip(poly, 2 * static_cast<int>(i) + (high ? 0 : 1), normal, offset, tolerance)) {
            case Clip::unchanged:
            case Clip::clipped: break;
            case Clip::empty: return 0.0; // cannot happen for slabs around one set of points
            case Clip::failed: return std::numeric_limits<double>::quiet_NaN();
            }
        }
    }

    // Volume by the divergence theorem: the sum over faces of area x distance from an inner point o, / 3.
    const glm::dvec3 o = base_inverse_ * (0.5 * (glm::dvec3(hi[base_[0]], hi[base_[1]], hi[base_[2]]) +
                                                 glm::dvec3(lo[base_[0]], lo[base_[1]], lo[base_[2]])));
    double volume = 0;
    for (int f = 0; f < poly.face_count; ++f) {
        const Polytope::Face& face = poly.faces[f];
        const glm::dvec3 normal = face.plane % 2 == 0 ? axes_[face.plane / 2] : -axes_[face.plane / 2];
        const glm::dvec3 v0 = poly.vertices[face.loop[0]];
        double area = 0;
        glm::dvec3 weighted(0.0);
        for (int k = 1; k + 1 < face.size; ++k) {
            const glm::dvec3 v1 = poly.vertices[face.loop[k]], v2 = poly.vertices[face.loop[k + 1]];
            const double triangle = 0.5 * glm::dot(glm::cross(v1 - v0, v2 - v0), normal);
            area += triangle;
            if (want_faces) weighted += triangle * (v0 + v1 + v2);
        }
        if (area <= 0) continue;
        volume += area * glm::dot(normal, v0 - o) / 3.0;
        if (want_faces) faces[face.plane] = {area, weighted / (3.0 * area)};
    }
    return std::max(volume, 0.0);
}

} // namespace kdop
