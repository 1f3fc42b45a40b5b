// How the emitter writes an axis, which the cost model counts by: each axis rescaled so that its
// largest component is exactly +1, and the paper's slab padding in the scaled axis's units.
#pragma once

#include <glm/vec3.hpp>

namespace kdop {

// Slab dilation of the paper (Sec. 3): 1e-5 per unit of axis length.
inline constexpr double kSlabPadding = 1e-5;

// An axis rescaled for emission. Clipping does not change when an axis is multiplied by any
// nonzero factor: a positive one scales slab, projection and ray alike, and a negative one swaps
// the slab's min and max. So each axis is multiplied by 1 / (its largest-magnitude component),
// which makes that component exactly +1.
struct ScaledAxis {
    glm::vec3 coefficients; // rounded to float once; the largest is exactly 1
    double factor;          // file axis x factor = coefficients
    float padding;          // kSlabPadding in the units of the scaled axis
};

ScaledAxis scale_axis(const glm::dvec3& axis);

} // namespace kdop
