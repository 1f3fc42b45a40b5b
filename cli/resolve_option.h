// The options of the TAA resolve (temporal/resolve_options.h), for every command that resolves
// frames: --history-filter, --color-map, --dilate-motion, --current-weight, --gamma.
#pragma once

#include "cli/color_map_option.h"
#include "cli/number_option.h"
#include "temporal/resolve_options.h"

#include <CLI/CLI.hpp>

#include <string>

namespace kdop::cli {

// `with_color_map` false leaves --color-map to the command (kdop optimize's fits in it too).
inline void add_resolve_options(CLI::App& app, ResolveOptions& options, bool with_color_map = true) {
    const CLI::Validator filter(
        [&options](std::string& text) -> std::string {
            auto parsed = parse_history_filter(text);
            if (!parsed) return parsed.error().message;
            options.history_filter = *parsed;
            return {};
        },
        "bilinear|catmull-rom");
    // The validator parses and stores the value; the option's own function has nothing left to do.
    auto stored = [](const std::string&) {};
    app.add_option_function<std::string>(
           "--history-filter", stored,
           "How the history is sampled at the reprojected position: bilinear, or catmull-rom (the 4x4 "
           "cubic, sharper; Tauray uses its 5-tap approximation) [default: bilinear]")
        ->check(filter);
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
}

} // namespace kdop::cli
