// --color-map, for every command that clips in a mapped space: the resolve's (kdop taa) and the
// fit's (kdop optimize). One spelling and one parser (core/color_map.h).
#pragma once

#include "core/color_map.h"

#include <CLI/CLI.hpp>

#include <string>

namespace kdop::cli {

inline CLI::Option* add_color_map_option(CLI::App& app, ColorMap& map, const std::string& description) {
    const CLI::Validator parse(
        [&map](std::string& text) -> std::string {
            auto parsed = parse_color_map(text);
            if (!parsed) return parsed.error().message;
            map = *parsed;
            return {};
        },
        "linear|gamma:G|log");
    // The validator parses and stores the value; the option's own function has nothing left to do.
    return app
        .add_option_function<std::string>(
            "--color-map", [](const std::string&) {}, description)
        ->check(parse);
}

} // namespace kdop::cli
