#include "core/color_map.h"

#include "core/shown_text.h"

#include <fmt/format.h>

#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include <charconv>
#include <cmath>

namespace kdop {

Result<ColorMap> parse_color_map(std::string_view text) {
    if (text == "linear") return ColorMap{};
    if (text == "log") return ColorMap{ColorMap::Kind::log, 1};
    constexpr std::string_view prefix = "gamma:";
    if (text.starts_with(prefix)) {
        // A decimal and nothing else: strtod took "0x10" as 16 and " 2" as 2.
        const std::string_view number = text.substr(prefix.size());
        double g = NAN;
        const auto [stop, error] =
            std::from_chars(number.data(), number.data() + number.size(), g, std::chars_format::general);
        if (number.empty() || error != std::errc{} || stop != number.data() + number.size() || !std::isfinite(g) ||
            g <= 0 || g > 100)
            return fail(fmt::format("'{}': the exponent of gamma:G must be a number from {} to 100",
                                    shown_text(text, 40), kMinColorMapExponent));
        if (g < kMinColorMapExponent)
            return fail(
                fmt::format("'{}': the exponent of gamma:G must be a number from {} to 100: the resolve maps "
                            "each color to c^G and back in float, which keeps it only to about 6e-8 / G of "
                            "itself{}; as G goes to 0 the map tends to the log one, which --color-map log "
                            "gives at full precision",
                            shown_text(text, 40), kMinColorMapExponent,
                            float(g) == 0 ? fmt::format(", and {} is 0 in float, mapping every color to 1", g) : ""));
        return ColorMap{ColorMap::Kind::power, g};
    }
    return fail(fmt::format("'{}' is not a color map; use linear, gamma:G (G from {} to 100) or log",
                            shown_text(text, 40), kMinColorMapExponent));
}

std::string to_string(const ColorMap& map) {
    switch (map.kind) {
    case ColorMap::Kind::power: return fmt::format("gamma:{}", map.exponent); // shortest round trip
    case ColorMap::Kind::log: return "log";
    case ColorMap::Kind::linear: break;
    }
    return "linear";
}

glm::vec3 map_color(const ColorMap& map, glm::vec3 c) {
    switch (map.kind) {
    case ColorMap::Kind::power: return glm::pow(glm::max(c, 0.0f), glm::vec3(float(map.exponent)));
    case ColorMap::Kind::log: return glm::log(glm::max(c, 0.0f) + kColorMapLogOffset);
    case ColorMap::Kind::linear: break;
    }
    return c;
}

Result<void> check_mappable(const ColorMap& map, std::span<const glm::vec4> pixels, std::uint32_t width,
                            std::string_view what) {
    // The log of a finite value is finite; only the power can overflow.
    if (map.kind != ColorMap::Kind::power) return {};
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        const glm::vec3 mapped = map_color(map, glm::vec3(pixels[i]));
        for (int c = 0; c < 3; ++c)
            if (std::isfinite(pixels[i][c]) && !std::isfinite(mapped[c]))
                return fail(fmt::format("{} pixel ({}, {}) has {} {}, which --color-map {} takes to {}, beyond float's "
                                        "range; use a smaller exponent or --color-map log",
                                        what, i % width, i / width, "RGB"[c], pixels[i][c], to_string(map), mapped[c]));
    }
    return {};
}

Result<void> map_colors(const ColorMap& map, std::span<glm::vec4> pixels, std::uint32_t width, std::string_view what) {
    if (map.kind == ColorMap::Kind::linear) return {};
    if (auto ok = check_mappable(map, pixels, width, what); !ok) return ok;
    for (glm::vec4& p : pixels) p = glm::vec4(map_color(map, glm::vec3(p)), p.a);
    return {};
}

} // namespace kdop
