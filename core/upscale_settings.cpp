#include "core/upscale_settings.h"

#include "core/shown_text.h"

#include <fmt/format.h>

#include <charconv>

namespace kdop {

Result<UpscaleFilter> parse_upscale_filter(std::string_view text) {
    if (text == "lanczos2") return UpscaleFilter::lanczos2;
    if (text == "gaussian") return UpscaleFilter::gaussian;
    return fail(fmt::format("'{}' is not an upscaling filter; use lanczos2 or gaussian", shown_text(text, 40)));
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

float box_scale_at(BoxScale scale, float ratio) {
    return scale == BoxScale::fsr2 ? 1.0f + 0.5f * (ratio - 1.0f) : 1.0f;
}

} // namespace kdop
