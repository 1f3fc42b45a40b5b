#include "temporal/resolve_options.h"

#include "core/shown_text.h"

#include <fmt/format.h>

namespace kdop {

Result<HistoryFilter> parse_history_filter(std::string_view text) {
    if (text == "bilinear") return HistoryFilter::bilinear;
    if (text == "catmull-rom") return HistoryFilter::catmull_rom;
    return fail(fmt::format("'{}' is not a history filter; use bilinear or catmull-rom", shown_text(text, 40)));
}

ResolveSettings resolve_settings(const ResolveOptions& o) {
    const ColorMapKind map = o.color_map.kind == ColorMap::Kind::power ? ColorMapKind::power
                             : o.color_map.kind == ColorMap::Kind::log ? ColorMapKind::log
                                                                       : ColorMapKind::linear;
    ResolveSettings settings{
        o.gamma,          o.current_weight, map, map == ColorMapKind::power ? o.color_map.exponent : 1.0,
        o.history_filter, o.dilate_motion};
    settings.upscaling = o.upscale;
    settings.upscale_filter = o.upscale_filter;
    settings.sample_distance = o.sample_distance;
    settings.box_scale = o.box_scale;
    return settings;
}

namespace {

// ", upscaling with the lanczos2 filter", and the sample distance and box scale where not the defaults.
std::string describe_upscaling(const ResolveOptions& o) {
    std::string text = fmt::format(", upscaling with the {} filter", to_string(o.upscale_filter));
    if (o.sample_distance.kind == SampleDistance::Kind::ue4)
        text += ", the clip's samples within UE4's distance (lerp(1.51, 1.3, ratio - 1) input pixels)";
    else if (o.sample_distance.kind == SampleDistance::Kind::fixed)
        text += fmt::format(", the clip's samples within {} input pixels", o.sample_distance.pixels);
    if (o.box_scale == BoxScale::fsr2) text += ", the variance clip widened with the ratio as FSR 2.0 widens its box";
    return text;
}

} // namespace

std::string describe(const ResolveOptions& o) {
    return fmt::format("{} history, {} colors{}, current weight {}, variance gamma {}{}", to_string(o.history_filter),
                       to_string(o.color_map), o.dilate_motion ? ", motion of the nearest neighbor" : "",
                       o.current_weight, o.gamma, o.upscale ? describe_upscaling(o) : "");
}

} // namespace kdop
