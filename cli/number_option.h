// The check of a real-valued option: a finite number in a range. CLI::Range and
// CLI::PositiveNumber let NaN through (every comparison with it is false) and word their bounds
// with all 309 digits of the largest double; this refuses NaN and the infinities and says the
// range as a person would.
#pragma once

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <string>

namespace kdop::cli {

// 31536000 rather than 3.1536e+07; 0.5 and 1e+30 as {:g} has them.
inline std::string shown_number(double v) {
    return v == std::floor(v) && std::abs(v) < 1e15 ? fmt::format("{:.0f}", v) : fmt::format("{:g}", v);
}

// A finite number from `min` to `max`, or, with `above_min`, above `min` and at most `max`.
inline CLI::Validator finite_number(double min, double max, bool above_min = false, const std::string& unit = "") {
    const std::string range = fmt::format("a number {} {} {} {}{}", above_min ? "above" : "from", shown_number(min),
                                          above_min ? "and at most" : "to", shown_number(max), unit);
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            double value = 0;
            if (!CLI::detail::lexical_cast(text, value)) return fmt::format("'{}' is not a number", text);
            if (!std::isfinite(value) || value < min || (above_min && value == min) || value > max)
                return fmt::format("'{}' is not {}", text, range);
            return {};
        },
        range);
}

// A finite number above 0 and at most `max`.
inline CLI::Validator positive_number(double max, const std::string& unit = "") {
    return finite_number(0, max, true, unit);
}

} // namespace kdop::cli
