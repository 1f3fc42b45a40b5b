// The invariants every rectified pixel must keep, checked against the double-precision reference
// (reference/cpu_clip.h). S is the pixel's magnitude: max(1, largest |channel| among the finite
// colors of its neighborhood, current and history). Float32 rounding grows with S, so every
// distance is measured in units of S and allowed kStressTolerance of it.
//
//   N finite     current finite -> output finite, whatever the history or a neighbor holds
//   D defined    current finite, history not usable (NaN, Inf, or too far out to project; see
//                reference_history_usable) -> output is exactly current
//   S segment    history usable -> output on the segment current..history
//   K inside     and all neighbors finite -> output inside every padded slab of the k-DOP
//   R range      and a clip whose axes include X, Y and Z -> every channel inside the
//                neighborhood's padded channel range (variance clips may leave it by design)
//   C classify   and GPU and reference disagree on whether the history is inside -> the history
//                lies on a slab, within the tolerance: the disagreement is rounding at the boundary
#pragma once

#include "generator/axis_set.h"
#include "generator/variant_spec.h"
#include "images/image.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace kdop {

// 1e-6 of S is about 17 float32 ulps: a projection, a min or max, the exit's subtraction and
// product, and the final multiply-add each round once, by at most half an ulp of a value no
// larger than 3 S (an axis scaled to a largest component of 1 has |components| summing to <= 3).
inline constexpr double kStressTolerance = 1e-6;

enum class Invariant { finite, defined, segment, inside, range, classify };
inline constexpr std::size_t kInvariantCount = 6;
inline constexpr Invariant kInvariants[] = {Invariant::finite, Invariant::defined, Invariant::segment,
                                            Invariant::inside, Invariant::range,   Invariant::classify};

const char* invariant_code(Invariant i);        // "N", "D", "S", "K", "R", "C"
const char* invariant_name(Invariant i);        // "finite", ...
const char* invariant_description(Invariant i); // one line, for reports

struct InvariantTally {
    std::size_t checked = 0, violated = 0;
    double worst = 0;    // largest distance seen, in units of S (S, K, R, C); 0 for N and D
    std::string example; // the first violation: pixel, inputs and output
};

struct CheckResult {
    std::size_t pixels = 0;
    std::array<InvariantTally, kInvariantCount> tallies;

    InvariantTally& operator[](Invariant i) { return tallies[static_cast<std::size_t>(i)]; }
    const InvariantTally& operator[](Invariant i) const { return tallies[static_cast<std::size_t>(i)]; }
    std::size_t violations() const;
};

// What is being checked: the variant's k-DOP as the reference builds it.
struct ClipUnderTest {
    ClipUnderTest(const VariantSpec& spec, double gamma);

    std::vector<glm::dvec3> unit_axes;
    bool has_xyz;
    Mode mode;
    Neighborhood neighborhood;
    double gamma;
    Numerics numerics;
};

// Every pixel of `output`, computed by the variant from `current` and `history`.
CheckResult check_invariants(const ClipUnderTest& clip, const Image& current, const Image& history,
                             const Image& output);

} // namespace kdop
