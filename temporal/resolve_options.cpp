#include "resolve_options.h"

#include "shown_text.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>

namespace kdop {

Result<HistoryFilter> parse_history_filter(std::string_view text) {
    if (text == "bilinear") return HistoryFilter::bilinear;
    if (text == "catmull-rom") return HistoryFilter::catmull_rom;
    return fail(fmt::format("'{}' is not a history filter; use bilinear or catmull-rom", shown_text(text, 40)));
}

Result<ColorMap> parse_color_map(std::string_view text) {
    if (text == "linear") return ColorMap{};
    if (text == "log") return ColorMap{ColorMap::Kind::log, 1};
    constexpr std::string_view prefix = "gamma:";
    if (text.starts_with(prefix)) {
        const std::string number(text.substr(prefix.size()));
        char* end = nullptr;
        const double g = number.empty() ? NAN : std::strtod(number.c_str(), &end);
        if (end && *end == '\0' && std::isfinite(g) && g > 0 && g <= 100)
            return ColorMap{ColorMap::Kind::power, float(g)};
        return fail(fmt::format("'{}': the exponent of gamma:G must be a number above 0 and at most 100",
                                shown_text(text, 40)));
    }
    return fail(fmt::format("'{}' is not a color map; use linear, gamma:G (G > 0) or log", shown_text(text, 40)));
}

std::string to_string(HistoryFilter filter) {
    return filter == HistoryFilter::catmull_rom ? "catmull-rom" : "bilinear";
}

std::string to_string(const ColorMap& map) {
    switch (map.kind) {
    case ColorMap::Kind::power: return fmt::format("gamma:{}", map.exponent);
    case ColorMap::Kind::log: return "log";
    case ColorMap::Kind::linear: break;
    }
    return "linear";
}

std::string describe(const ResolveOptions& o) {
    return fmt::format("{} history, {} colors{}, current weight {}, variance gamma {}", to_string(o.history_filter),
                       to_string(o.color_map), o.dilate_motion ? ", motion of the nearest neighbor" : "",
                       o.current_weight, o.gamma);
}

} // namespace kdop
