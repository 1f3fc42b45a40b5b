// The ideal clip, the reference for accuracy: how far the ray from the current color toward the
// history stays inside the convex hull of the neighborhood's colors (DESIGN.md, "ideal clip").
//
// It is the linear program
//     maximize t  over  lambda_i >= 0, s >= 0, t >= 0
//     subject to  sum_i lambda_i p_i = s c + t h,   sum_i lambda_i = 1,   s + t = 1
// (the point (1 - t) c + t h is a convex combination of the neighborhood colors p_i). Written this
// way every coefficient is an input color as given (times one power of two, see ideal_clip.cpp),
// never a rounded difference, so GLPK's rational simplex (glp_exact) solves it exactly for those
// inputs; t is rounded to double once, at the end (toward zero). An LP needs no special case for
// degenerate hulls: a flat, line or point neighborhood only makes rows dependent (a hull library
// would need each of those projected to its own dimension first).
#pragma once

#include "core/result.h"
#include "generator/variant_spec.h"
#include "images/image.h"

#include <glm/vec3.hpp>

#include <optional>
#include <span>
#include <vector>

struct glp_prob;

namespace kdop {

// One LP, reused from pixel to pixel. Not thread-safe: one per thread (GLPK's state is per thread).
class IdealClipper {
public:
    IdealClipper();
    ~IdealClipper();
    IdealClipper(const IdealClipper&) = delete;
    IdealClipper& operator=(const IdealClipper&) = delete;

    // The largest t in [0, 1] with current + t (history - current) inside the convex hull of
    // `neighborhood`: 1 when the history lies inside. Empty when `current` itself lies outside the
    // hull (it never does when it is one of the neighborhood's colors); NaN if GLPK fails (past its
    // iteration limit, or colors too far apart in magnitude to scale to integers; neither is
    // known to happen). Every input must be finite.
    std::optional<double> exit(std::span<const glm::dvec3> neighborhood, const glm::dvec3& current,
                               const glm::dvec3& history);

private:
    glp_prob* lp_;
    int columns_ = 0; // neighborhood colors the LP has columns for
};

// The ideal exit of every pixel (row-major), with the neighborhood gathered like the shaders and
// the CPU reference (clamp-to-edge, the pixel itself included), on one thread per core. Both
// images must have the same size and finite RGB. Fails, naming the pixel, if an LP has no optimum
// (which would be a bug: the current color is always in its own neighborhood).
Result<std::vector<double>> ideal_exits(const Image& current, const Image& history, Neighborhood shape);

} // namespace kdop
