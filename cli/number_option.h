// The checks of numeric options, one wording for all of them ("--gamma: '-1' is not a number above
// 0 and at most 100"), each a usage error (exit 2): a finite number in a range, a whole number in a
// range, a thread count. CLI::Range and CLI::PositiveNumber let NaN through (every comparison with
// it is false), word their bounds with all 309 digits of the largest double, and take "-1" for an
// unsigned option as 2^64 - 1 or fail its conversion with a message of their own; these refuse NaN,
// the infinities and every value outside the range, and say the range as a person would. Numbers
// are read as decimals only: CLI11 converts with strtold, which also takes "0x10" as 16, "0x1p4",
// " 5" and "infinity", none of which a person means as a plain number.
#pragma once

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <limits>
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
            // std::from_chars in the general format: digits, '.', an exponent and a leading '-', and
            // nothing before or after them ("inf" and "nan" it reads, and the range refuses).
            double value = 0;
            const char* end = text.data() + text.size();
            auto [stop, error] = std::from_chars(text.data(), end, value, std::chars_format::general);
            if (text.empty() || stop != end || (error != std::errc{} && error != std::errc::result_out_of_range))
                return fmt::format("'{}' is not a number", text);
            if (error != std::errc{} || !std::isfinite(value) || value < min || (above_min && value == min) ||
                value > max)
                return fmt::format("'{}' is not {}", text, range);
            return {};
        },
        range);
}

// A finite number above 0 and at most `max`.
inline CLI::Validator positive_number(double max, const std::string& unit = "") {
    return finite_number(0, max, true, unit);
}

// A whole number from `min` to `max`, checked on the text before CLI11 converts it, so "-1" for an
// unsigned option and "1e3" are refused in the same words as a value out of range.
inline CLI::Validator whole_number(long long min, long long max, const std::string& unit = "") {
    const std::string range = fmt::format("a whole number from {} to {}{}", min, max, unit);
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            long long value = 0;
            const char* end = text.data() + text.size();
            auto [stop, error] = std::from_chars(text.data(), end, value);
            if (text.empty() || error != std::errc{} || stop != end || value < min || value > max)
                return fmt::format("'{}' is not {}", text, range);
            return {};
        },
        range);
}

// A seed: any whole number that is not negative and fits a signed 64-bit integer.
inline CLI::Validator seed_number() { return whole_number(0, std::numeric_limits<long long>::max()); }

// The variance clip's width in standard deviations, for every command that takes --gamma.
inline CLI::Validator gamma_number() { return positive_number(100); }

// Threads: at most kMaxThreads, far beyond any machine kdop runs on; a larger count would only
// spawn threads until the process or the PID space runs out.
inline constexpr long long kMaxThreads = 1024;
inline CLI::Validator thread_count() { return whole_number(1, kMaxThreads); }

} // namespace kdop::cli
