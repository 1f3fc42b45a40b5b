#include "sequence/jitter.h"

#include <cmath>

namespace kdop {

glm::vec2 r2_point(std::uint32_t index) {
    // R2: the plastic number g solves g^3 = g + 1; entry n is frac(0.5 + n * (1/g, 1/g^2)).
    constexpr double g = 1.32471795724474602596;
    const double n = index;
    const double x = 0.5 + n / g, y = 0.5 + n / (g * g);
    return {float(x - std::floor(x) - 0.5), float(y - std::floor(y) - 0.5)};
}

} // namespace kdop
