// A WIDTHxHEIGHT option (`bench --size`, `taa --size`): both sides 8..16384, and the rectification
// pass at that size must fit the memory budget (core/memory_budget.h).
#pragma once

#include "core/memory_budget.h"
#include "core/result.h"

#include <fmt/format.h>

#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace kdop::cli {

using Size = std::pair<std::uint32_t, std::uint32_t>; // width, height

// "1920x1080" -> {1920, 1080}; both sides 8..16384.
inline std::optional<Size> parse_size(std::string_view text) {
    const auto x = text.find('x');
    if (x == std::string_view::npos) return std::nullopt;
    auto number = [](std::string_view s) -> std::optional<std::uint32_t> {
        std::uint32_t v = 0;
        auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (error != std::errc{} || end != s.data() + s.size() || v < 8 || v > 16384) return std::nullopt;
        return v;
    };
    auto w = number(text.substr(0, x)), h = number(text.substr(x + 1));
    if (!w || !h) return std::nullopt;
    return Size{*w, *h};
}

inline Result<Size> size_option(const std::string& option, const std::string& text) {
    auto size = parse_size(text);
    if (!size) return fail(fmt::format("{}: '{}' is not WIDTHxHEIGHT with sides 8..16384", option, text));
    if (auto ok = check_memory(fmt::format("{} {}", option, text), rectify_pass_bytes(size->first, size->second)); !ok)
        return std::unexpected(ok.error());
    return *size;
}

} // namespace kdop::cli
