// An RGBA float image in memory: what kdop reads, generates, uploads and compares. RGB are linear
// color values (any range: HDR, negative and non-finite values are kept as they are); alpha is
// carried along and set to 1 where a source has none.
#pragma once

#include <glm/vec4.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace kdop {

struct Image {
    std::uint32_t width = 0, height = 0;
    std::vector<glm::vec4> pixels; // row-major

    Image() = default;
    Image(std::uint32_t w, std::uint32_t h, glm::vec4 fill = {0, 0, 0, 1})
        : width(w), height(h), pixels(std::size_t(w) * h, fill) {}

    glm::vec4& at(std::uint32_t x, std::uint32_t y) { return pixels[std::size_t(y) * width + x]; }
    const glm::vec4& at(std::uint32_t x, std::uint32_t y) const { return pixels[std::size_t(y) * width + x]; }

    // The pixel at (x, y) with coordinates clamped into the image (clamp-to-edge addressing).
    const glm::vec4& clamped(int x, int y) const {
        return at(static_cast<std::uint32_t>(std::clamp(x, 0, static_cast<int>(width) - 1)),
                  static_cast<std::uint32_t>(std::clamp(y, 0, static_cast<int>(height) - 1)));
    }
};

} // namespace kdop
