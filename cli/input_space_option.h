// `--input-space`, for every command that reads images: how their values become linear RGB
// (images/image_io.h). By default each file says (float formats linear, 8- and 16-bit ones sRGB
// unless tagged otherwise); `linear` or `srgb` overrides every file.
#pragma once

#include "images/image_io.h"

#include <CLI/CLI.hpp>

#include <string>

namespace kdop::cli {

inline CLI::Option* add_input_space_option(CLI::App& app, InputSpace& space) {
    // The name becomes the enumerator's number, which CLI11 then stores.
    const CLI::Validator by_name(
        [](std::string& text) -> std::string {
            const auto parsed = parse_input_space(text);
            if (!parsed) return "'" + text + "' is not file, linear or srgb";
            text = std::to_string(static_cast<int>(*parsed));
            return {};
        },
        "");
    return app
        .add_option("--input-space", space,
                    "How the input images' values become linear RGB: file (float formats such as EXR are linear; "
                    "8- and 16-bit ones such as PNG and JPEG are decoded from sRGB unless tagged linear), or linear "
                    "or srgb for every file [default: file]")
        ->transform(by_name)
        ->type_name("file|linear|srgb");
}

} // namespace kdop::cli
