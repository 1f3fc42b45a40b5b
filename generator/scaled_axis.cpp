#include "generator/scaled_axis.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace kdop {

ScaledAxis scale_axis(const glm::dvec3& axis) {
    int largest = 0;
    for (int c = 1; c < 3; ++c)
        if (std::abs(axis[c]) > std::abs(axis[largest])) largest = c;
    ScaledAxis scaled;
    scaled.factor = 1.0 / axis[largest];
    // Divided rather than multiplied by the factor, which is infinite for a denormal largest component.
    const glm::dvec3 unit_largest = axis / axis[largest];
    for (int c = 0; c < 3; ++c) scaled.coefficients[c] = static_cast<float>(unit_largest[c]) + 0.0f; // -0 -> +0
    scaled.coefficients[largest] = 1.0f;
    // |axis| * |factor| as the length of the scaled axis, which is at most sqrt(3): no overflow for
    // an axis of 1e200, no underflow for one of 1e-200.
    scaled.padding = static_cast<float>(kSlabPadding * glm::length(unit_largest));
    return scaled;
}

} // namespace kdop
