// The space a clip works in: linear values, c^G, or log(c + 1e-5). The TAA resolve clips and blends
// there (--color-map, as the paper's own renderer maps colors: Tauray's map_color), and an axis set
// fitted for such a resolve is fitted there (kdop optimize --color-map, recorded in the set's file
// as `color_map:`). Negative values map as 0.
#pragma once

#include "core/result.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <span>
#include <string>
#include <string_view>

namespace kdop {

struct ColorMap {
    enum class Kind { linear, power, log };
    Kind kind = Kind::linear;
    float exponent = 1; // Kind::power only: > 0

    bool operator==(const ColorMap&) const = default;
};

// The offset log(c + kLogOffset) keeps black finite (Tauray floors at 1e-5 instead, which is not
// monotonic below it).
inline constexpr float kColorMapLogOffset = 1e-5f;

// "linear", "gamma:G" (G finite, above 0 and at most 100) or "log".
Result<ColorMap> parse_color_map(std::string_view text);
std::string to_string(const ColorMap& map);

// One color in the map's space, in float as the resolve's shader computes it.
glm::vec3 map_color(const ColorMap& map, glm::vec3 color);

// Refuses the first pixel whose color `map` takes beyond what float holds (c^G above 3.4e38: 60000
// under gamma:10, 1e20 under gamma:2), naming `what`, the pixel (of an image `width` wide), the
// value and the map: the resolve would turn it black and a fit would hand infinities to its solver.
Result<void> check_mappable(const ColorMap& map, std::span<const glm::vec4> pixels, std::uint32_t width,
                            std::string_view what);
// Every pixel's RGB mapped in place (an Image's pixels), alpha kept, after check_mappable.
Result<void> map_colors(const ColorMap& map, std::span<glm::vec4> pixels, std::uint32_t width, std::string_view what);

} // namespace kdop
