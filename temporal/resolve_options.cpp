#include "temporal/resolve_options.h"

#include "core/shown_text.h"

#include <fmt/format.h>

#include <charconv>

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

float SampleDistance::at(float ratio) const {
    if (kind == Kind::fixed) return pixels;
    if (kind == Kind::ue4) return 1.51f + (1.3f - 1.51f) * (ratio - 1.0f);
    return 1e30f; // every neighbor: none of the 3x3 lies that far
}

Result<SampleDistance> parse_sample_distance(std::string_view text) {
    if (text == "all") return SampleDistance{};
    if (text == "ue4") return SampleDistance{SampleDistance::Kind::ue4, 0};
    // A plain decimal, as the commands' numbers are read (cli/number_option.h).
    double pixels = 0;
    const char* end = text.data() + text.size();
    auto [stop, error] = std::from_chars(text.data(), end, pixels, std::chars_format::general);
    if (text.empty() || stop != end || error != std::errc{} || !(pixels > 0) || pixels > 4)
        return fail(fmt::format("'{}' is not a sample distance; use all, ue4 or a number of input pixels above 0 and "
                                "at most 4",
                                shown_text(text, 40)));
    return SampleDistance{SampleDistance::Kind::fixed, float(pixels)};
}

std::string to_string(const SampleDistance& d) {
    if (d.kind == SampleDistance::Kind::ue4) return "ue4";
    if (d.kind == SampleDistance::Kind::fixed) return fmt::format("{}", d.pixels);
    return "all";
}

Result<BoxScale> parse_box_scale(std::string_view text) {
    if (text == "none") return BoxScale::none;
    if (text == "fsr2") return BoxScale::fsr2;
    return fail(fmt::format("'{}' is not a box scale; use none or fsr2", shown_text(text, 40)));
}

const char* to_string(BoxScale scale) { return scale == BoxScale::fsr2 ? "fsr2" : "none"; }

float box_scale_at(BoxScale scale, float ratio) {
    return scale == BoxScale::fsr2 ? 1.0f + 0.5f * (ratio - 1.0f) : 1.0f;
}

ResolveSettings resolve_settings(const ResolveOptions& o) {
    const ColorMapKind map = o.color_map.kind == ColorMap::Kind::power ? ColorMapKind::power
                             : o.color_map.kind == ColorMap::Kind::log ? ColorMapKind::log
                                                                       : ColorMapKind::linear;
    return {o.gamma,          o.current_weight, map, map == ColorMapKind::power ? o.color_map.exponent : 1.0,
            o.history_filter, o.dilate_motion};
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
