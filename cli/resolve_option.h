// The options of the TAA resolve (temporal/resolve_options.h), for every command that resolves
// frames: --history-filter, --color-map, --dilate-motion, --current-weight, --gamma, and for
// sources that upscale --upscale-filter, --upscale-sample-distance and --upscale-box-scale.
#pragma once

#include "cli/color_map_option.h"
#include "cli/number_option.h"
#include "temporal/resolve_options.h"

#include <CLI/CLI.hpp>

#include <string>

namespace kdop::cli {

// Option `name`, whose text `parse` reads into `target` (a Result); `shown` is what the help says
// it takes. A text `parse` refuses is a usage error with its message.
template <class T, class Parse>
void add_parsed_option(CLI::App& app, const std::string& name, T& target, Parse parse, const std::string& shown,
                       const std::string& help) {
    const CLI::Validator parsed(
        [&target, parse](std::string& text) -> std::string {
            auto value = parse(text);
            if (!value) return value.error().message;
            target = *value;
            return {};
        },
        shown);
    // The validator has stored the value; the option's own function has nothing left to do.
    app.add_option_function<std::string>(
           name, [](const std::string&) {}, help)
        ->check(parsed);
}

// How a resolve upscales, for sources whose frames are smaller than their output (docs/taa.md,
// "Upscaling"); a source that does not upscale ignores them.
inline void add_upscale_options(CLI::App& app, ResolveOptions& options) {
    add_parsed_option(app, "--upscale-filter", options.upscale_filter, parse_upscale_filter, "lanczos2|gaussian",
                      "Where a source upscales: how the resolve reconstructs each output pixel's current color from "
                      "the input samples around it: lanczos2 (clamped to the neighborhood's range, as FSR 2) or "
                      "gaussian [default: lanczos2]");
    add_parsed_option(app, "--upscale-sample-distance", options.sample_distance, parse_sample_distance, "all|ue4|D",
                      "Where a source upscales: which neighbors of the nearest input sample the clip keeps: all, "
                      "those whose samples lie within D input pixels of the output pixel's center, or ue4 (UE4's "
                      "TAAU: lerp(1.51, 1.3, ratio - 1)) [default: all]");
    add_parsed_option(app, "--upscale-box-scale", options.box_scale, parse_box_scale, "none|fsr2",
                      "Where a source upscales: widen the variance clip with the ratio: none, or fsr2 (gamma times 1 "
                      "+ (ratio - 1) / 2, as FSR 2.0 widens its box) [default: none]");
}

// `with_color_map` false leaves --color-map to the command (kdop optimize's fits in it too).
inline void add_resolve_options(CLI::App& app, ResolveOptions& options, bool with_color_map = true) {
    add_parsed_option(app, "--history-filter", options.history_filter, parse_history_filter, "bilinear|catmull-rom",
                      "How the history is sampled at the reprojected position: bilinear, or catmull-rom (the 4x4 "
                      "cubic, sharper; Tauray uses its 5-tap approximation) [default: bilinear]");
    if (with_color_map)
        add_color_map_option(
            app, options.color_map,
            "The space the clip and the blend work in: linear, gamma:G (values raised to G, G from 0.01 "
            "to 100, as the paper's own renderer maps them; gamma:0.5 is a square root) or log (log(c + 1e-5), which "
            "damps bright outliers) [default: linear]");
    app.add_flag("--dilate-motion", options.dilate_motion,
                 "Take the motion of the nearest of the 3x3 neighbors by depth, so edges follow the nearer surface "
                 "(needs depth on every frame)");
    app.add_option("--current-weight", options.current_weight, "The current frame's share of the blend [default: 0.1]")
        ->check(finite_number(0, 1, true));
    app.add_option("--gamma", options.gamma, "The variance clip's width in standard deviations [default: 1]")
        ->check(gamma_number());
    add_upscale_options(app, options);
}

} // namespace kdop::cli
