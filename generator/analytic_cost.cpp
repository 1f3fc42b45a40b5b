#include "analytic_cost.h"

#include "glsl_emitter.h"
#include "variant_spec.h"

#include <algorithm>
#include <cassert>

namespace kdop {

std::size_t frame_float_ops(const AxisSet& set, Mode mode, Neighborhood neighborhood, bool relative) {
    assert(mode == Mode::clip || mode == Mode::varclip);
    const std::size_t n = neighborhood_offsets(neighborhood).size();
    std::size_t ops = 18; // ray direction; usable history; current + t * dir
    if (relative || mode == Mode::varclip) ops += 3 * (n - 1);
    if (mode == Mode::varclip) ops += 11; // the scaled frame
    for (const Axis& axis : set.axes) {
        // Counted on the scaled axis the emitter writes, whose zero components are those of the file.
        const ScaledAxis scaled = scale_axis(axis.direction);
        std::size_t m = 0;
        for (int c = 0; c < 3; ++c) m += scaled.coefficients[c] != 0.0f;
        if (mode == Mode::varclip)
            ops += n * (m - 1) + 2 * n + 11;
        else if (relative)
            ops += n * (m - 1) + 2 * (n - 1) + 3;
        else
            ops += (n + 1) * (m - 1) + 2 * n + 3;
    }
    return ops;
}

std::size_t analytic_min_float_ops(const AxisSet& set, Mode mode, Neighborhood neighborhood) {
    return std::min(frame_float_ops(set, mode, neighborhood, true), frame_float_ops(set, mode, neighborhood, false));
}

} // namespace kdop
