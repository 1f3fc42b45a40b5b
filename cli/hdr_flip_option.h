// HDR-FLIP's options (flip/hdr_flip.h), for every command that measures HDR content (`kdop flip
// --hdr`, `kdop taa` on HDR sequences): --tone-mapper, --start-exposure, --stop-exposure and
// --exposures. Each stores into ExposureOptions; one not given stays unset and is derived from
// each pair's reference, as NVlabs/flip derives it.
#pragma once

#include "cli/number_option.h"
#include "flip/hdr_flip.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace kdop::cli {

// Returns the options added, for `needs` and for telling whether one was given.
inline std::vector<CLI::Option*> add_hdr_flip_options(CLI::App& app, ExposureOptions& options) {
    const CLI::Validator tone_mapper(
        [&options](std::string& text) -> std::string {
            auto parsed = parse_tone_mapper(text);
            if (!parsed) return "'" + text + "' is not aces, hable or reinhard";
            options.tone_mapper = *parsed;
            return {};
        },
        "aces|hable|reinhard");
    return {
        app.add_option_function<std::string>(
               "--tone-mapper", [](const std::string&) {},
               "HDR-FLIP's tone mapper: aces, hable or reinhard [default: aces]")
            ->check(tone_mapper),
        app.add_option_function<double>(
               "--start-exposure", [&options](double e) { options.start = float(e); },
               "HDR-FLIP's first exposure in stops [default: from the reference's largest luminance, as "
               "NVlabs/flip derives it]")
            ->check(finite_number(-1000, 1000)),
        app.add_option_function<double>(
               "--stop-exposure", [&options](double e) { options.stop = float(e); },
               "HDR-FLIP's last exposure in stops [default: from the reference's median luminance]")
            ->check(finite_number(-1000, 1000)),
        app.add_option_function<int>(
               "--exposures", [&options](int n) { options.count = n; },
               "HDR-FLIP's number of exposures, from 1 to 1000 [default: max(2, ceil(stop - start))]")
            ->check(whole_number(1, 1000)),
    };
}

} // namespace kdop::cli
