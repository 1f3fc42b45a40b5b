#include "sequence/jitter.h"

#include <algorithm>
#include <cmath>

namespace kdop {

glm::vec2 r2_point(std::uint32_t index) {
    // R2: the plastic number g solves g^3 = g + 1; entry n is frac(0.5 + n * (1/g, 1/g^2)).
    constexpr double g = 1.32471795724474602596;
    const double n = index;
    const double x = 0.5 + n / g, y = 0.5 + n / (g * g);
    return {float(x - std::floor(x) - 0.5), float(y - std::floor(y) - 0.5)};
}

std::uint32_t upscale_jitter_phases(double ratio) { return std::uint32_t(std::ceil(8.0 * ratio * ratio - 1e-9)); }

namespace {

// The radical inverse of n in `base`: the Halton sequence's coordinate of that base.
double radical_inverse(std::uint32_t n, std::uint32_t base) {
    double value = 0, scale = 1.0 / base;
    for (; n > 0; n /= base, scale /= base) value += double(n % base) * scale;
    return value;
}

} // namespace

glm::vec2 halton_jitter(std::uint32_t index, std::uint32_t phases) {
    const std::uint32_t n = index % std::max(phases, 1u) + 1;
    return {float(radical_inverse(n, 2) - 0.5), float(radical_inverse(n, 3) - 0.5)};
}

} // namespace kdop
