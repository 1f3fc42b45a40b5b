#include "temporal/resolve_options.h"

#include "core/shown_text.h"

#include <fmt/format.h>

namespace kdop {

Result<HistoryFilter> parse_history_filter(std::string_view text) {
    if (text == "bilinear") return HistoryFilter::bilinear;
    if (text == "catmull-rom") return HistoryFilter::catmull_rom;
    return fail(fmt::format("'{}' is not a history filter; use bilinear or catmull-rom", shown_text(text, 40)));
}

Result<UpscaleFilter> parse_upscale_filter(std::string_view text) {
    if (text == "lanczos2") return UpscaleFilter::lanczos2;
    if (text == "gaussian") return UpscaleFilter::gaussian;
    return fail(fmt::format("'{}' is not an upscaling filter; use lanczos2 or gaussian", shown_text(text, 40)));
}

const char* to_string(UpscaleFilter filter) { return filter == UpscaleFilter::gaussian ? "gaussian" : "lanczos2"; }

ResolveSettings resolve_settings(const ResolveOptions& o) {
    const ColorMapKind map = o.color_map.kind == ColorMap::Kind::power ? ColorMapKind::power
                             : o.color_map.kind == ColorMap::Kind::log ? ColorMapKind::log
                                                                       : ColorMapKind::linear;
    return {o.gamma,          o.current_weight, map, map == ColorMapKind::power ? o.color_map.exponent : 1.0,
            o.history_filter, o.dilate_motion};
}

std::string describe(const ResolveOptions& o) {
    return fmt::format("{} history, {} colors{}, current weight {}, variance gamma {}{}", to_string(o.history_filter),
                       to_string(o.color_map), o.dilate_motion ? ", motion of the nearest neighbor" : "",
                       o.current_weight, o.gamma,
                       o.upscale ? fmt::format(", upscaling with the {} filter", to_string(o.upscale_filter)) : "");
}

} // namespace kdop
