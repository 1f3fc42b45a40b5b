// The choices of the TAA resolve (shader_templates/taa_resolve.comp.in) a user makes on the
// command line. The defaults are the textbook resolve the paper's tables were measured with in
// kdop; the others follow the paper's own renderer (Tauray, shader/taa.comp). Each choice is a
// compile-time define of the resolve, as a renderer would build its permutations: no branch in
// the shader tests an option.
#pragma once

#include "core/color_map.h"
#include "core/result.h"
#include "core/upscale_settings.h"

#include <kdop/variant.h> // HistoryFilter, UpscaleFilter, SampleDistance, BoxScale, ResolveSettings

#include <string>
#include <string_view>

namespace kdop {

struct ResolveOptions {
    HistoryFilter history_filter = HistoryFilter::bilinear;
    ColorMap color_map;               // the space the clip and the blend happen in (color_map.h)
    bool dilate_motion = false;       // the motion of the nearest 3x3 neighbor, by depth
    bool depth_nearer_larger = false; // the sequence's depth convention (reversed Z), for dilate_motion
    // The current frame's share of the blend. The introduction to TAA in shared/reference gives 0.05
    // to 0.1 as the usual range; at 0.1 the history averages about ten frames, the length of the R2
    // jitter cycle.
    float current_weight = 0.1f;
    float gamma = 1; // variance-clip width; Salvi's recommended 1, as in the paper's +Var rows
    UpscaleFilter upscale_filter = UpscaleFilter::lanczos2; // for sources whose output is larger than their input
    bool upscale = false;           // the source's: input smaller than the output (set by the evaluation per source)
    SampleDistance sample_distance; // for upscaling sources
    BoxScale box_scale = BoxScale::none; // for upscaling sources
    // Every output the filtered current color, no history: the spatial-only upscale kdop taa puts
    // beside the variants (set by the evaluation for that row alone).
    bool no_history = false;
};

// "all", "ue4" or a number of input pixels above 0 and at most 4.
Result<SampleDistance> parse_sample_distance(std::string_view text);
std::string to_string(const SampleDistance& distance);
// "none" or "fsr2" (to_string in kdop/variant.h spells it).
Result<BoxScale> parse_box_scale(std::string_view text);
// The factor the variance clip's gamma is multiplied by at upscaling ratio `ratio`.
float box_scale_at(BoxScale scale, float ratio);

// "bilinear" or "catmull-rom" (to_string in kdop/variant.h spells it).
Result<HistoryFilter> parse_history_filter(std::string_view text);

// What the options say, for a report: "bilinear history, linear colors, w = 0.1", and with
// `upscale` the filter.
std::string describe(const ResolveOptions& options);

// The options as a manifest records them and a registry declares them (kdop/variant.h); the
// sequence's depth convention is the sequence's, not the resolve's, and stays out.
ResolveSettings resolve_settings(const ResolveOptions& options);

} // namespace kdop
