// The fewest scalar float operations kdop's clip formulation (hardened numerics, see EmitStyle)
// needs for an axis set: the yardstick the cost bench holds each emitted variant against
// (analytic_min_ops in cost.csv). Counted like count_float_ops(): a multiply-add is one operation,
// a vector operation one per component.
//
// Per slab, for an axis with m nonzero components and a neighborhood of N colors (the pixel's own
// among them):
//   projections   (N + 1)(m - 1)  the N colors and the ray direction; scaled so one component is
//                                 exactly 1, an axis costs m - 1 multiply-adds per projection, and
//                                 the pixel's projection doubles as the ray origin's
//   clip extent   2(N - 1)        min and max over N projections
//   varclip slab  2N + 9          N - 1 adds and a scale for the mean, N multiply-adds, a scale, a
//                                 multiply-add and a scale for the variance, its clamp at 0 and
//                                 sqrt, mean -/+ gamma * sigma (2), and widening to contain the
//                                 origin (2)
//   dilation      2               lo - padding * scale, hi + padding * scale (one multiply-add each)
//   exit          6 (clip)        reciprocal of the direction's projection, compare and select
//                 5 (varclip)     for the plane the ray heads for, minus the origin (clip only),
//                                 times the reciprocal, min into t
// Per pixel: the ray direction (3 subtracts); the padding scale, max(1, |current| channels) (3
// abs, 3 max); whether the history is usable, |dir|_1 + |current|_1 <= FLT_MAX (3 abs, 3 + 2
// adds, a compare); current + max(t, 0) * dir (a max and 3 multiply-adds; the unusable case
// returns current through a branch, no select); for varclip -gamma (1), the power-of-two scale
// of the relative frame (a compare, two selects, -current * scale (3), the ray (3) and the
// padding (1) scaled) and the colors relative to current (3N multiply-adds).
//
// Not counted, because the formulation does not need them: starting the running extents from
// +-FLT_MAX (2 per clip slab), which the emitter does on purpose because it measured cheaper on
// lavapipe; see write_clip_slab() in glsl_emitter.cpp.
#pragma once

#include "axis_set.h"

#include <kdop/variant.h>

#include <cstddef>

namespace kdop {

// Only for the clips (Mode::clip, Mode::varclip); either form computes the same function, so the
// minimum does not depend on the form.
std::size_t analytic_min_float_ops(const AxisSet& set, Mode mode, Neighborhood neighborhood);

} // namespace kdop
