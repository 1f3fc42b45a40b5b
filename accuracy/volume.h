// Volumes for the accuracy report, through Qhull (the reentrant libqhull_r): the convex hull of a
// neighborhood's colors, and the k-DOP a variant builds around it as the intersection of its slabs.
#pragma once

#include "core/result.h"
#include "reference/cpu_clip.h"

#include <glm/vec3.hpp>

#include <span>

namespace kdop {

// The volume of the convex hull of `points`; 0 when they do not span three dimensions (Qhull
// finds no initial simplex). Points must be finite.
Result<double> hull_volume(std::span<const glm::dvec3> points);

// The volume of the intersection of `slabs`. `interior` must lie strictly inside every slab, and
// the axes must span three dimensions (otherwise the intersection is unbounded: an error).
Result<double> slab_volume(std::span<const ReferenceSlab> slabs, const glm::dvec3& interior);

} // namespace kdop
