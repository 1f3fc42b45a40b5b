#include "generator/axis_set.h"

#include "core/utf8.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <clocale>
#include <cmath>
#include <cstdlib>
#include <locale.h>
#include <optional>

namespace kdop {

glm::dvec3 unit_direction(const glm::dvec3& direction) {
    const double largest = std::max({std::abs(direction.x), std::abs(direction.y), std::abs(direction.z)});
    return glm::normalize(direction / largest);
}

namespace {

// Beyond this the generated shader grows past anything worth shipping (a 128-DOP unrolled over a
// 3x3 neighborhood is already ~1,200 projections); refusing early gives a clear message instead.
constexpr size_t kMaxAxes = 64;

// Below this |det| three unit axes count as coplanar: the k-DOP they bound would be a slab so
// elongated that float32 clipping against it is meaningless.
constexpr double kMinSpanDeterminant = 1e-6;

std::string_view trim(std::string_view s) {
    const char* ws = " \t\r\n";
    size_t b = s.find_first_not_of(ws);
    if (b == std::string_view::npos) return {};
    size_t e = s.find_last_not_of(ws);
    return s.substr(b, e - b + 1);
}

bool is_space(char c) { return c == ' ' || c == '\t'; }

// A token as messages quote it: at most 40 characters, bytes that are not printable ASCII as \xNN,
// so whatever a file holds, the terminal shows text, not escape sequences or a 100 KB line.
std::string quoted(std::string_view token) {
    std::string out;
    for (std::size_t i = 0; i < token.size() && i < 40; ++i) {
        const unsigned char c = static_cast<unsigned char>(token[i]);
        out += c >= 0x20 && c < 0x7f ? std::string(1, char(c)) : fmt::format("\\x{:02x}", c);
    }
    return "'" + out + (token.size() > 40 ? "'…" : "'");
}

Result<double> parse_number(std::string_view token, const std::string& where) {
    // One leading '+' is allowed, in front of digits only ("+-1" is not a number).
    std::string_view digits = token.starts_with('+') ? token.substr(1) : token;
    if (token.starts_with('+') && (digits.starts_with('+') || digits.starts_with('-')))
        return fail(fmt::format("{}{} is not a number", where, quoted(token)));
    // strtod in the "C" locale: the same in every program that links kdop, whatever locale it set.
    // Hex floats, which strtod would take, are not a spelling axis files have.
    static const locale_t c_locale = newlocale(LC_ALL_MASK, "C", locale_t(0));
    const std::string text(digits);
    if (text.empty() || text.find_first_of("xX") != std::string::npos ||
        std::isspace(static_cast<unsigned char>(text[0])))
        return fail(fmt::format("{}{} is not a number", where, quoted(token)));
    char* end = nullptr;
    errno = 0;
    const double value = strtod_l(text.c_str(), &end, c_locale);
    if (end != text.c_str() + text.size()) return fail(fmt::format("{}{} is not a number", where, quoted(token)));
    // ERANGE also marks a denormal, which is a number; only overflow and underflow to 0 are out of range.
    if (errno == ERANGE && (std::isinf(value) || value == 0))
        return fail(fmt::format("{}{} is out of range for a double", where, quoted(token)));
    return value;
}

// The first byte of `line` that is a control character (tab aside), or -1. Such a byte would end
// the comment a name or provenance is copied into in generated code, and has no place in a number.
int control_character(std::string_view line) {
    for (char ch : line) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if ((c < 0x20 && c != '\t') || c == 0x7f) return c;
    }
    return -1;
}

// Splits "x y z", "x, y, z" or "x,y,z" into number tokens; an empty field ("1,,0") is an error.
Result<std::vector<std::string_view>> split_numbers(std::string_view s, const std::string& where) {
    std::vector<std::string_view> tokens;
    size_t i = 0;
    while (i < s.size()) {
        size_t start = i;
        while (i < s.size() && !is_space(s[i]) && s[i] != ',') ++i;
        if (i == start) return fail(where + "empty number between commas");
        tokens.push_back(s.substr(start, i - start));
        while (i < s.size() && is_space(s[i])) ++i;
        if (i < s.size() && s[i] == ',') {
            ++i;
            while (i < s.size() && is_space(s[i])) ++i;
            if (i == s.size()) return fail(where + "line ends with a comma after the last number");
        }
    }
    return tokens;
}

// The numbers of one axis line, with an optional vec3(...) wrapper and one trailing comma.
Result<glm::dvec3> parse_axis_line(std::string_view line, const std::string& where) {
    if (line.ends_with(',')) line = trim(line.substr(0, line.size() - 1));
    if (line.starts_with("vec3")) {
        std::string_view inner = trim(line.substr(4));
        if (!inner.starts_with('(') || !inner.ends_with(')')) return fail(where + "expected vec3(x, y, z)");
        line = trim(inner.substr(1, inner.size() - 2));
    }
    auto tokens = split_numbers(line, where);
    if (!tokens) return std::unexpected(tokens.error());
    if (tokens->size() != 3) return fail(fmt::format("{}expected 3 numbers (x y z), found {}", where, tokens->size()));
    glm::dvec3 v;
    for (int c = 0; c < 3; ++c) {
        auto number = parse_number((*tokens)[c], where);
        if (!number) return std::unexpected(number.error());
        v[c] = *number;
    }
    return v;
}

std::optional<Error> check_axis(const Axis& axis, const std::vector<Axis>& earlier, const std::string& where) {
    for (int c = 0; c < 3; ++c) {
        if (std::isnan(axis.direction[c])) return Error{where + "axis component is NaN"};
        if (std::isinf(axis.direction[c])) return Error{where + "axis component is infinite"};
    }
    // Directions are compared as unit vectors, normalized after scaling by the largest component so
    // that neither 1e200 (whose square overflows) nor 1e-200 (whose square underflows) is misread.
    if (axis.direction == glm::dvec3(0)) return Error{where + "axis has zero length"};
    const glm::dvec3 unit = unit_direction(axis.direction);
    for (const Axis& other : earlier) {
        const glm::dvec3 other_unit = unit_direction(other.direction);
        if (glm::length(glm::cross(unit, other_unit)) >= kParallelAxisAngle) continue;
        if (glm::dot(unit, other_unit) > 0)
            return Error{fmt::format("{}axis duplicates the axis on line {}", where, other.line)};
        return Error{
            fmt::format("{}axis is antiparallel to the axis on line {} (both bound the same slab)", where, other.line)};
    }
    return std::nullopt;
}

bool spans_3d(const std::vector<Axis>& axes) {
    for (size_t i = 0; i < axes.size(); ++i)
        for (size_t j = i + 1; j < axes.size(); ++j)
            for (size_t k = j + 1; k < axes.size(); ++k) {
                glm::dvec3 a = unit_direction(axes[i].direction), b = unit_direction(axes[j].direction),
                           c = unit_direction(axes[k].direction);
                if (std::abs(glm::dot(a, glm::cross(b, c))) >= kMinSpanDeterminant) return true;
            }
    return false;
}

} // namespace

std::optional<std::string> fitted_space_mismatch(const AxisSet& set, const ColorMap& used, std::string_view clipping) {
    if (!set.color_map || *set.color_map == used) return std::nullopt;
    return fmt::format("set '{}' was fitted in {} space (color_map: in {}), and {} clips in {} space: it is not the "
                       "fit this clip needs; fit it again with kdop optimize --color-map {}",
                       set.name, to_string(*set.color_map), set.origin, clipping, to_string(used), to_string(used));
}

Result<AxisSet> parse_axis_set(std::string_view text, std::string_view origin) {
    AxisSet set;
    set.origin = std::string(origin);
    int name_line = 0, provenance_line = 0, color_map_line = 0;
    int line_number = 0;
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3); // a UTF-8 byte-order mark some editors write
    while (!text.empty()) {
        size_t eol = text.find('\n');
        std::string_view raw = text.substr(0, eol);
        text = eol == std::string_view::npos ? std::string_view{} : text.substr(eol + 1);
        ++line_number;
        std::string where = fmt::format("{}:{}: ", origin, line_number);
        if (raw.ends_with('\r')) raw.remove_suffix(1); // CRLF line ends
        if (int c = control_character(raw); c >= 0)
            return fail(fmt::format("{}control character 0x{:02x}; axis files are plain text", where, c));
        // The provenance is written into JSON (kdop gen's variants.json, kdop-gen --json), which holds
        // only UTF-8: a Latin-1 "café" must be refused here, by line, not by the JSON writer at the end.
        if (auto at = first_non_utf8_byte(raw))
            return fail(fmt::format("{}byte 0x{:02x} (column {}) is not UTF-8; axis files are UTF-8 text", where,
                                    static_cast<unsigned char>(raw[*at]), *at + 1));

        std::string_view line = trim(raw.substr(0, raw.find('#')));
        if (line.empty()) continue;

        size_t colon = line.find(':');
        bool is_key = colon != std::string_view::npos && colon > 0 &&
                      line.substr(0, colon).find_first_not_of("abcdefghijklmnopqrstuvwxyz_") == std::string_view::npos;
        if (is_key) {
            std::string_view key = line.substr(0, colon);
            std::string_view value = trim(line.substr(colon + 1));
            int* seen = key == "name"         ? &name_line
                        : key == "provenance" ? &provenance_line
                        : key == "color_map"  ? &color_map_line
                                              : nullptr;
            if (!seen)
                return fail(
                    fmt::format("{}unknown key '{}' (expected 'name:', 'provenance:' or 'color_map:')", where, key));
            if (*seen) return fail(fmt::format("{}second '{}:' line (the first is on line {})", where, key, *seen));
            if (value.empty()) return fail(fmt::format("{}'{}:' has no value", where, key));
            *seen = line_number;
            if (key == "name") {
                if (!is_valid_set_name(value))
                    return fail(
                        fmt::format("{}set name {} is not valid: use lowercase letters and digits, "
                                    "starting with a letter, with single '-' between words (at most 48 characters)",
                                    where, quoted(value)));
                set.name = std::string(value);
            } else if (key == "color_map") {
                auto map = parse_color_map(value);
                if (!map) return fail(fmt::format("{}color_map: {}", where, map.error().message));
                set.color_map = *map;
            } else {
                set.provenance = std::string(value);
            }
            continue;
        }

        auto direction = parse_axis_line(line, where);
        if (!direction) return std::unexpected(direction.error());
        Axis axis{*direction, line_number};
        if (auto error = check_axis(axis, set.axes, where)) return std::unexpected(*error);
        if (set.axes.size() == kMaxAxes)
            return fail(fmt::format("{}more than {} axes (a {}-DOP); kdop refuses sets this large", where, kMaxAxes,
                                    2 * kMaxAxes));
        set.axes.push_back(axis);
    }

    if (!name_line) return fail(fmt::format("{}: missing 'name:' line", origin));
    if (!provenance_line)
        return fail(fmt::format("{}: missing 'provenance:' line (say where the numbers come from)", origin));
    if (!spans_3d(set.axes))
        return fail(fmt::format("{}: the {} axes do not span 3-D space (fewer than 3, or all in one plane), "
                                "so the k-DOP would not bound a region",
                                origin, set.axes.size()));
    return set;
}

} // namespace kdop
