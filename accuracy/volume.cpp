#include "accuracy/volume.h"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace kdop {
namespace {

// One Qhull run: its state, and its error stream captured in memory for our message.
class QhullRun {
public:
    QhullRun() : errors_(open_memstream(&error_text_, &error_size_)) { qh_zero(&qh_, errors_); }
    ~QhullRun() {
        int curlong, totlong;
        qh_freeqhull(&qh_, !qh_ALL);
        qh_memfreeshort(&qh_, &curlong, &totlong);
        if (errors_) std::fclose(errors_);
        std::free(error_text_);
    }
    QhullRun(const QhullRun&) = delete;
    QhullRun& operator=(const QhullRun&) = delete;

    // Returns Qhull's exit code (qh_ERRnone on success). `coordinates` stays Qhull's to read.
    int run(int dimension, std::vector<double>& coordinates, std::string flags) {
        return qh_new_qhull(&qh_, dimension, static_cast<int>(coordinates.size()) / dimension, coordinates.data(),
                            False, flags.data(), nullptr, errors_);
    }
    qhT* qh() { return &qh_; }
    std::string error() {
        std::fflush(errors_);
        std::string text = error_text_ ? std::string(error_text_, error_size_) : std::string();
        return text.substr(0, text.find('\n'));
    }

private:
    qhT qh_;
    char* error_text_ = nullptr;
    std::size_t error_size_ = 0;
    FILE* errors_;
};

} // namespace

Result<double> hull_volume(std::span<const glm::dvec3> points) {
    std::vector<double> coordinates;
    for (const glm::dvec3& p : points) coordinates.insert(coordinates.end(), {p.x, p.y, p.z});
    // Points in a plane of constant R, G or B (a single repeated point among them) are flat; Qhull
    // reports those as an input error rather than as singular, so they are decided here.
    if (points.size() < 4) return 0.0;
    for (int k = 0; k < 3; ++k)
        if (std::all_of(points.begin(), points.end(), [&](const glm::dvec3& p) { return p[k] == points[0][k]; }))
            return 0.0;
    QhullRun qhull;
    // FA: compute the volume. Qt: triangulate the output (coplanar input points merge into facets
    // rather than stopping Qhull).
    const int status = qhull.run(3, coordinates, "qhull FA Qt");
    if (status == qh_ERRsingular) return 0.0; // flat, a line or a point: no initial simplex
    if (status != qh_ERRnone) return fail(fmt::format("Qhull: {}", qhull.error()));
    return qhull.qh()->totvol;
}

Result<double> slab_volume(std::span<const ReferenceSlab> slabs, const glm::dvec3& interior) {
    // Halfspaces for Qhull's H mode, as (normal, offset) with normal . x + offset <= 0.
    std::vector<double> halfspaces;
    for (const ReferenceSlab& s : slabs) {
        halfspaces.insert(halfspaces.end(), {s.axis.x, s.axis.y, s.axis.z, -s.hi});
        halfspaces.insert(halfspaces.end(), {-s.axis.x, -s.axis.y, -s.axis.z, s.lo});
    }
    std::vector<glm::dvec3> vertices;
    {
        QhullRun qhull;
        // H<point>: intersect the halfspaces around this interior point (printed exactly).
        const int status =
            qhull.run(4, halfspaces, fmt::format("qhull H{:.17g},{:.17g},{:.17g}", interior.x, interior.y, interior.z));
        if (status != qh_ERRnone) return fail(fmt::format("Qhull (slab intersection): {}", qhull.error()));
        // Each facet of the dual hull is one vertex of the intersection (Qhull's 'Fp' output).
        qhT* qh = qhull.qh();
        for (facetT* facet = qh->facet_list; facet && facet->next; facet = facet->next) {
            glm::dvec3& v = vertices.emplace_back();
            for (int k = 0; k < 3; ++k) v[k] = -facet->normal[k] / facet->offset + qh->feasible_point[k];
            if (!std::isfinite(v.x + v.y + v.z))
                return fail("slab intersection is unbounded: the axes do not span three dimensions");
        }
    }
    return hull_volume(vertices);
}

} // namespace kdop
