// A variant named on the command line (`run --variant`, `show NAME`) with an optional --numerics:
// `--numerics paper` names the same variant's paper twin, as its -paper name does.
#pragma once

#include "core/variant_key.h"

#include <fmt/format.h>

#include <string>
#include <string_view>

namespace kdop::cli {

// `numerics` is the option's value, empty when not given (CLI11 has checked its spelling).
inline Result<VariantKey> variant_option(std::string_view name, const std::string& numerics, std::string_view option) {
    auto key = parse_variant_key(name, option);
    if (!key || numerics.empty()) return key;
    if (!key->is_clip()) return fail(fmt::format("--numerics: {} is not a clip", name));
    if (key->numerics == Numerics::paper && numerics != "paper")
        return fail(fmt::format("--numerics: {} conflicts with the variant's own -paper", numerics));
    return key->with(*parse_numerics(numerics));
}

} // namespace kdop::cli
