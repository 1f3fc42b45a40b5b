// How an upscaling TAA resolve upscales, as the command lines and a manifest spell it
// (--upscale-filter, --upscale-sample-distance, --upscale-box-scale; the manifest's
// upscale-filter:, upscale-sample-distance: and upscale-box-scale: lines). The types are public
// (kdop/variant.h), so an engine builds its resolve from the manifest's record.
#pragma once

#include "core/result.h"

#include <kdop/variant.h> // UpscaleFilter, SampleDistance, BoxScale

#include <string>
#include <string_view>

namespace kdop {

// "lanczos2" or "gaussian" (to_string in kdop/variant.h spells it).
Result<UpscaleFilter> parse_upscale_filter(std::string_view text);

// "all", "ue4" or a number of input pixels above 0 and at most 4.
Result<SampleDistance> parse_sample_distance(std::string_view text);
std::string to_string(const SampleDistance& distance);

// "none" or "fsr2" (to_string in kdop/variant.h spells it).
Result<BoxScale> parse_box_scale(std::string_view text);
// The factor the variance clip's gamma is multiplied by at upscaling ratio `ratio`.
float box_scale_at(BoxScale scale, float ratio);

} // namespace kdop
