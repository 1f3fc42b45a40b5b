// A lower bound on the scalar float operations of kdop's hardened clip for an axis set: the
// yardstick the cost bench holds each emitted variant against (analytic_min_ops in cost.csv).
// Counted like count_float_ops(): a multiply-add is one operation, a vector operation one per
// component, a select one, integer operations (the sign-bit test) none. Lavapipe emits no fused
// multiply-add, so there each Fma becomes a multiply and an add: the counts here and lavapipe's
// instructions disagree by the number of Fmas, beyond its 8 pixels per SIMD instruction.
// The derivation, per pixel and per slab for each frame and the variance clip, is in
// docs/clip.md, "The analytic bound".
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
