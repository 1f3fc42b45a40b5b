// The magma color map, as NVlabs/flip shows its error maps: an error in [0, 1] picks one of 256
// colors (black through purple and orange to pale yellow), the nearest of value * 255.
#pragma once

#include "images/image.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>

namespace kdop::flip {

// The color for `value` as the table holds it: sRGB-encoded, in [0, 1].
glm::vec3 magma_srgb(float value);

// An image of `values` (width * height of them, row-major) in magma, holding LINEAR values as
// every kdop image does: written as PNG (tagged linear) it shows the map's colors, though its bytes
// are not the sRGB-encoded ones of the reference tool's PNG.
Image magma_image(std::span<const float> values, std::uint32_t width, std::uint32_t height);

} // namespace kdop::flip
