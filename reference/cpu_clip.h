// The CPU reference of k-DOP clipping, in double precision, written from the paper's definitions
// and independently of the generator's emitter: GPU results are checked against it.
//
// Clip: each axis a (normalized) gives a slab [min q - e, max q + e] of the neighborhood's
// projections q = c . a, dilated by the paper's e = 1e-5. Variance clip: the slab is mean +- gamma *
// sigma of the projections (population variance), widened to contain the current color's
// projection, then dilated by e. The ray from the current color toward the history leaves the
// k-DOP at the smallest exit parameter over the slabs; the result is
// current + clamp(t, 0, 1) * (history - current). A slab the ray runs parallel to never limits t.
// Both numerics compute this function; kdop's hardened numerics also keep it at the extremes (where
// float32 loses the paper's e above about 84), and replace a history that is not usable by the
// current color: one with a NaN or Inf channel, or one where |history - current|_1 + |current|_1
// exceeds FLT_MAX (past which float32 projections of the ray could overflow; the generated shaders
// promise no more).
#pragma once

#include "generator/axis_set.h"
#include "generator/variant_spec.h"
#include "images/image.h"

#include <kdop/variant.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <span>
#include <vector>

namespace kdop {

// The paper's slab dilation, per unit of axis length: e above.
inline constexpr double kReferencePadding = 1e-5;

// Whether the history takes part at all (see above); if not, the result is `current`.
bool reference_history_usable(const glm::dvec3& current, const glm::dvec3& history);

// One slab of the padded k-DOP: the points x with lo <= x . axis <= hi.
struct ReferenceSlab {
    glm::dvec3 axis; // normalized
    double lo, hi;
};

// The padded k-DOP of a neighborhood around `current` (varclip widens each slab to contain it).
std::vector<ReferenceSlab> reference_slabs(std::span<const glm::dvec3> unit_axes,
                                           std::span<const glm::dvec3> neighborhood, const glm::dvec3& current,
                                           Mode mode, double gamma);

// Where the ray current + t (history - current) leaves the slabs, clamped to [0, 1]: 1 when the
// history lies inside. Takes the history as given (no usability rule).
double reference_exit(std::span<const ReferenceSlab> slabs, const glm::dvec3& current, const glm::dvec3& history);

// One pixel: current + reference_exit(...) * (history - current), or, hardened, current where the
// history is not usable (the paper's numerics use any history as it is). `unit_axes` must be
// normalized; `mode` is clip or varclip.
glm::dvec3 reference_clip(std::span<const glm::dvec3> unit_axes, std::span<const glm::dvec3> neighborhood,
                          const glm::dvec3& current, const glm::dvec3& history, Mode mode, double gamma,
                          Numerics numerics = Numerics::hardened);

std::vector<glm::dvec3> unit_axes(const AxisSet& set);

// Texel offsets of a neighborhood shape (order irrelevant to the result).
std::vector<glm::ivec2> reference_offsets(Neighborhood n);

// The neighborhood of pixel (x, y) at `offsets`, with clamp-to-edge addressing, into `out`.
void gather_neighborhood(const Image& image, std::uint32_t x, std::uint32_t y, std::span<const glm::ivec2> offsets,
                         std::span<glm::dvec3> out);

// Every pixel of an image pair: the neighborhood is gathered from `current` with clamp-to-edge
// addressing, the current color is the pixel itself. Alpha of the result is 1.
Image reference_rectify(const AxisSet& set, Mode mode, Neighborhood n, const Image& current, const Image& history,
                        double gamma, Numerics numerics = Numerics::hardened);

} // namespace kdop
