#include "analytic_cost.h"

#include "glsl_emitter.h"
#include "variant_spec.h"

#include <cassert>

namespace kdop {

std::size_t analytic_min_float_ops(const AxisSet& set, Mode mode, Neighborhood neighborhood) {
    assert(mode == Mode::clip || mode == Mode::varclip);
    const std::size_t n = neighborhood_offsets(neighborhood).size();
    // Ray direction; padding scale; usable history; current + max(t, 0) * dir.
    std::size_t ops = 3 + 6 + 9 + 4;
    if (mode == Mode::varclip) ops += 1 + 10 + 3 * n; // -gamma; the scaled frame; colors relative to current
    for (const Axis& axis : set.axes) {
        // Counted on the scaled axis the emitter writes, whose zero components are those of the file.
        const ScaledAxis scaled = scale_axis(axis.direction);
        std::size_t nonzero = 0;
        for (int c = 0; c < 3; ++c) nonzero += scaled.coefficients[c] != 0.0f;
        ops += (n + 1) * (nonzero - 1);
        ops += mode == Mode::clip ? 2 * (n - 1) : 2 * n + 9;
        ops += 2;                          // dilation
        ops += mode == Mode::clip ? 6 : 5; // exit
    }
    return ops;
}

} // namespace kdop
