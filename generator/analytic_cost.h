// A lower bound on the scalar float operations of kdop's hardened clip for an axis set: the
// yardstick the cost bench holds each emitted variant against (analytic_min_ops in cost.csv).
// Counted like count_float_ops(): a multiply-add is one operation, a vector operation one per
// component, a select one, integer operations (the sign-bit test) none. Lavapipe emits no fused
// multiply-add, so there each Fma becomes a multiply and an add: the counts here and lavapipe's
// instructions disagree by the number of Fmas, beyond its 8 pixels per SIMD instruction.
//
// The function: per slab, the extent of the neighbors' projections (or mean +- gamma * sigma of
// them, widened to contain the current color's), padded by the paper's 1e-5 per unit of axis length
// after it is measured from the current color, which stands for the center pixel; the ray's exit
// through the plane it heads for. For an axis with m nonzero components (scaled so one is exactly 1,
// each projection costs m - 1 multiply-adds) and a neighborhood of N colors:
//
//   per pixel     18 + 3(N - 1)   ray direction (3); whether the history is usable,
//                 (relative)      |dir|_1 + |current|_1 <= FLT_MAX (3 + 3 abs, 3 + 2 adds, a
//                                 compare); current + t * dir (3 multiply-adds; the unusable case
//                                 returns current through a branch); and, relative, the N - 1
//                                 neighbors minus current
//                 18 (absolute)
//   clip slab     N(m - 1) + 2N + 3                relative: the N - 1 neighbors' and the ray's
//                                                  projections; min and max of the neighbors and
//                                                  the center (0); the padding (2); the exit (a
//                                                  select of the plane, a division, a min into t)
//                 (N + 1)(m - 1) + 2N + 5          absolute: the current color's projection too;
//                                                  min and max of N - 1 projections (2(N - 2)),
//                                                  minus that projection (2), joined with the
//                                                  center (2); the padding; the exit
//   varclip       per pixel 18 + 3(N - 1) + 11     the power-of-two scale of the relative frame
//                                                  (the largest |current| channel by 2 max, a
//                                                  compare, two selects, origin and ray scaled)
//                 per slab N(m - 1) + 2N + 11      the N - 1 projections and the ray's; the sum
//                                                  (N - 2 adds) and the mean (1); the variance
//                                                  (N - 1 squares, 3 more) and sigma (max, sqrt);
//                                                  mean -/+ gamma * sigma joined with the origin
//                                                  and padded (6); the exit
//
// An axis whose two scaled components have one magnitude (YCoCg's Y and Cg) projects them as
// (c.a +- c.b) * k: one multiply-add per projection on a sum that every axis with the same pair
// shares, once per color.
//
// The bound is the cheaper frame. The emitted variance clip spends up to 1 per slab more (where
// spirv-opt leaves a negation unfolded), which the tests allow for and no more. The emitter takes the cheaper one too
// (hardened_frame below), but starts the absolute frame's running extents from +-FLT_MAX (2 per slab more),
// which it does on purpose because it measured cheaper on lavapipe; see write_clip_slab().
#pragma once

#include "generator/axis_set.h"
#include "generator/scaled_axis.h"

#include <kdop/variant.h>

#include <cstddef>

namespace kdop {

// Where a hardened clip measures its slabs from. Absolute: the colors as they are, minus the current
// color's projection once per slab. Relative: the colors minus the current color, three subtracts
// per neighbor once, after which the origin is 0 and every slab is cheaper. The emitter takes the
// cheaper for the set (hardened_frame below: relative for the k-DOPs, absolute for the AABBs in n9);
// the variance clip is always relative, as its moments need.
enum class Frame { absolute, relative };

// Only for the clips (Mode::clip, Mode::varclip); either form computes the same function, so the
// bound does not depend on the form.
std::size_t analytic_min_float_ops(const AxisSet& set, Mode mode, Neighborhood neighborhood);

// The same count in one frame (a clip's varclip is always relative), without the emitter's
// deliberate constant starts.
std::size_t frame_float_ops(const AxisSet& set, Mode mode, Neighborhood neighborhood, bool relative);

// The frame the emitter writes a hardened clip in: the one whose emitted code counts fewer float
// ops (the absolute frame's with its constant starts); absolute on a tie. Varclip: relative.
Frame hardened_frame(const AxisSet& set, Mode mode, Neighborhood neighborhood);

} // namespace kdop
