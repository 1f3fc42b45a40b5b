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
// A simple polytope with F faces has at most 2F - 4 vertices and 3F - 6 edges; clipping keeps the
// vertices it cuts away until the next pass, so room for twice that.
constexpr int kMaxVertices = 4 * kMaxPlanes;
constexpr int kMaxLoop = 12 * kMaxPlanes;

// A convex polytope as faces: each a loop of vertex indices, counter-clockwise seen from outside.
struct Polytope {
    glm::dvec3 vertices[kMaxVertices];
    int vertex_count = 0;
    int face_plane[kMaxPlanes]; // 2i: x . a_i <= hi_i, 2i+1: x . a_i >= lo_i
    int face_start[kMaxPlanes];
    int face_size[kMaxPlanes];
    int face_count = 0;
    int loop[kMaxLoop];
    int loop_size = 0;
};

enum class Clip { unchanged, clipped, empty, failed };

// Keeps the part of `in` where n . x <= d, as `out`, whose new face lies on plane `plane`. A vertex
// within `tolerance` of the plane counts as on it (inside), so a face nearly in the plane is kept
// whole instead of cut into slivers whose order rounding could scramble.
Clip clip(const Polytope& in, Polytope& out, int plane, const glm::dvec3& n, double d, double tolerance) {
    double side[kMaxVertices];
    bool any_out = false, any_in = false;
    for (int i = 0; i < in.vertex_count; ++i) {
        side[i] = glm::dot(n, in.vertices[i]) - d;
        if (side[i] > tolerance)
            any_out = true;
        else
            any_in = true;
    }
    if (!any_out) return Clip::unchanged;
    if (!any_in) return Clip::empty;

    int kept[kMaxVertices]; // in's vertex -> out's, or -1
    std::fill_n(kept, in.vertex_count, -1);
    struct Cut {
        int inside, outside, vertex;
    };
    Cut cuts[kMaxVertices];
    int cut_count = 0;
    int cap_next[kMaxVertices]; // out's vertex on the new face -> the next one around it
    out.vertex_count = out.face_count = out.loop_size = 0;

    auto keep = [&](int v) {
        if (kept[v] < 0) {
            kept[v] = out.vertex_count;
            out.vertices[out.vertex_count++] = in.vertices[v];
        }
        return kept[v];
    };
    // The point where edge inside-outside meets the plane, made once for both faces of the edge.
    auto cut = [&](int inside, int outside) {
        for (int c = 0; c < cut_count; ++c)
            if (cuts[c].inside == inside && cuts[c].outside == outside) return cuts[c].vertex;
        const double t = side[inside] / (side[inside] - side[outside]);
        const int v = out.vertex_count++;
        out.vertices[v] = in.vertices[inside] + t * (in.vertices[outside] - in.vertices[inside]);
        cap_next[v] = -1;
        cuts[cut_count++] = {inside, outside, v};
        return v;
    };
    auto outside = [&](int v) { return side[v] > tolerance; };

    for (int f = 0; f < in.face_count; ++f) {
        const int* loop = in.loop + in.face_start[f];
        const int size = in.face_size[f];
        const int start = out.loop_size;
        int exit = -1, entry = -1, exits = 0;
        for (int k = 0; k < size; ++k) {
            const int u = loop[k], w = loop[(k + 1) % size];
            if (!outside(u)) out.loop[out.loop_size++] = keep(u);
            if (!outside(u) && outside(w)) {
                exit = cut(u, w);
                out.loop[out.loop_size++] = exit;
                ++exits;
            } else if (outside(u) && !outside(w)) {
                entry = cut(w, u);
                out.loop[out.loop_size++] = entry;
            }
        }
        if (exits > 1) return Clip::failed; // only a convex face crosses the plane once each way
        if (out.loop_size - start < 3) {     // all outside, or a sliver of no area
            out.loop_size = start;
            continue;
        }
        // This face runs exit -> entry along the plane; the new face, its neighbor there, runs back.
        if (exits) cap_next[entry] = exit;
        out.face_plane[out.face_count] = in.face_plane[f];
        out.face_start[out.face_count] = start;
        out.face_size[out.face_count++] = out.loop_size - start;
    }

    // The new face: follow the links from any point where an edge was cut.
    const int first = cuts[0].vertex, start = out.loop_size;
    int v = first;
    do {
        if (v < 0 || out.loop_size - start > cut_count) return Clip::failed;
        out.loop[out.loop_size++] = v;
        v = cap_next[v];
    } while (v != first);
    if (out.loop_size - start >= 3) {
        out.face_plane[out.face_count] = plane;
        out.face_start[out.face_count] = start;
        out.face_size[out.face_count++] = out.loop_size - start;
    } else {
        out.loop_size = start;
    }
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

double KdopPolytope::volume_of(std::span<const glm::dvec3> points, std::span<Face> faces) const {
    double lo[kMaxPolytopeAxes], hi[kMaxPolytopeAxes];
    for (std::size_t i = 0; i < axes_.size(); ++i) {
        lo[i] = std::numeric_limits<double>::infinity();
        hi[i] = -lo[i];
        for (const glm::dvec3& p : points) {
            const double q = glm::dot(axes_[i], p);
            lo[i] = std::min(lo[i], q);
            hi[i] = std::max(hi[i], q);
        }
    }
    return volume({lo, axes_.size()}, {hi, axes_.size()}, faces);
}

double KdopPolytope::volume_gradient(std::span<const glm::dvec3> points, std::span<glm::dvec3> gradient) const {
    const std::size_t n = axes_.size();
    double lo[kMaxPolytopeAxes], hi[kMaxPolytopeAxes];
    std::size_t lowest[kMaxPolytopeAxes], highest[kMaxPolytopeAxes];
    for (std::size_t i = 0; i < n; ++i) {
        lo[i] = hi[i] = glm::dot(axes_[i], points[0]);
        lowest[i] = highest[i] = 0;
        for (std::size_t j = 1; j < points.size(); ++j) {
            const double q = glm::dot(axes_[i], points[j]);
            if (q < lo[i]) lo[i] = q, lowest[i] = j;
            if (q > hi[i]) hi[i] = q, highest[i] = j;
        }
    }
    Face faces[2 * kMaxPolytopeAxes];
    const double v = volume({lo, n}, {hi, n}, {faces, 2 * n});
    if (std::isnan(v)) return v;
    for (std::size_t i = 0; i < n; ++i)
        gradient[i] += faces[2 * i].area * (points[highest[i]] - faces[2 * i].centroid) +
                       faces[2 * i + 1].area * (faces[2 * i + 1].centroid - points[lowest[i]]);
    return v;
}

double KdopPolytope::sphere_volume_gradient(std::span<glm::dvec3> gradient) const {
    const std::size_t n = axes_.size();
    const std::vector<double> lo(n, -1.0), hi(n, 1.0);
    Face faces[2 * kMaxPolytopeAxes];
    const double v = volume(lo, hi, {faces, 2 * n});
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
    Polytope polytopes[2];
    Polytope* p = &polytopes[0];
    for (int b = 0; b < 8; ++b) {
        glm::dvec3 q;
        for (int k = 0; k < 3; ++k) q[k] = (b >> k & 1) ? hi[base_[k]] : lo[base_[k]];
        p->vertices[b] = base_inverse_ * q;
    }
    p->vertex_count = 8;
    // Face (k, high): the vertices with bit k equal to `high`, around the other two bits. The cycle
    // 00 -> 01 -> 11 -> 10 of bits (k+1, k+2) is counter-clockwise from outside on the high face of
    // a right-handed frame; low faces and a left-handed (flipped) frame run it backwards.
    for (int k = 0; k < 3; ++k)
        for (int high = 0; high < 2; ++high) {
            const int bit1 = 1 << ((k + 1) % 3), bit2 = 1 << ((k + 2) % 3), fixed = high ? 1 << k : 0;
            int cycle[4] = {fixed, fixed | bit1, fixed | bit1 | bit2, fixed | bit2};
            if (!high != base_flipped_) std::swap(cycle[1], cycle[3]);
            p->face_plane[p->face_count] = 2 * static_cast<int>(base_[k]) + (high ? 0 : 1);
            p->face_start[p->face_count] = p->loop_size;
            p->face_size[p->face_count++] = 4;
            for (int v : cycle) p->loop[p->loop_size++] = v;
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
            Polytope* q = p == &polytopes[0] ? &polytopes[1] : &polytopes[0];
            switch (clip(*p, *q, 2 * static_cast<int>(i) + (high ? 0 : 1), normal, offset, tolerance)) {
            case Clip::unchanged: break;
            case Clip::clipped: p = q; break;
            case Clip::empty: return 0.0; // cannot happen for slabs around one set of points
            case Clip::failed: return std::numeric_limits<double>::quiet_NaN();
            }
        }
    }

    // Volume by the divergence theorem: the sum over faces of area x distance from an inner point o, / 3.
    const glm::dvec3 o = base_inverse_ * (0.5 * (glm::dvec3(hi[base_[0]], hi[base_[1]], hi[base_[2]]) +
                                glm::dvec3(lo[base_[0]], lo[base_[1]], lo[base_[2]])));
    double volume = 0;
    for (int f = 0; f < p->face_count; ++f) {
        const int plane = p->face_plane[f];
        const glm::dvec3 normal = plane % 2 == 0 ? axes_[plane / 2] : -axes_[plane / 2];
        const int* loop = p->loop + p->face_start[f];
        const glm::dvec3 v0 = p->vertices[loop[0]];
        double area = 0;
        glm::dvec3 weighted(0.0);
        for (int k = 1; k + 1 < p->face_size[f]; ++k) {
            const glm::dvec3 v1 = p->vertices[loop[k]], v2 = p->vertices[loop[k + 1]];
            const double triangle = 0.5 * glm::dot(glm::cross(v1 - v0, v2 - v0), normal);
            area += triangle;
            weighted += triangle * (v0 + v1 + v2) / 3.0;
        }
        if (area <= 0) continue;
        volume += area * glm::dot(normal, v0 - o) / 3.0;
        if (want_faces) faces[plane] = {area, weighted / area};
    }
    return std::max(volume, 0.0);
}

} // namespace kdop
