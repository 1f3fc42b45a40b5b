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
    // Kind::power only, from kMinColorMapExponent to 100: the value given, kept whole, so every file
    // that records the map records what the user wrote (gamma:1.00000001 was written as gamma:1);
    // the resolve computes with it in float, as map_color does.
    double exponent = 1;

    bool operator==(const ColorMap&) const = default;
};

// The smallest gamma:G. The resolve maps each color to c^G and back in float, which keeps a color
// only to about 6e-8 / G of itself (measured: 5.8e-6 at 0.01, 0.006 at 1e-5, more than an 8-bit
// step), and gamma:1e-300 is 0 in float, mapping every color to 1. As G goes to 0, c^G tends to
// 1 + G log c: the log map, which --color-map log gives at full precision.
inline constexpr double kMinColorMapExponent = 0.01;

// The offset log(c + kLogOffset) keeps black finite (Tauray floors at 1e-5 instead, which is not
// monotonic below it).
inline constexpr float kColorMapLogOffset = 1e-5f;

// "linear", "gamma:G" (G a decimal number from kMinColorMapExponent to 100) or "log".
Result<ColorMap> parse_color_map(std::string_view text);
// The map as parse_color_map reads it, G in the shortest form that reads back as the same double.
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
