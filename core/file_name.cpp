#include "core/file_name.h"

#include <fmt/format.h>

namespace kdop {
namespace {

// The length of the UTF-8 sequence at text[i] and its code point, or 0 where it is not valid
// (RFC 3629: no overlong forms, no surrogates, nothing past U+10FFFF).
std::size_t utf8_sequence(std::string_view text, std::size_t i, char32_t& code_point) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char lead = byte(i);
    std::size_t length;
    char32_t lowest;
    if (lead < 0x80) {
        code_point = lead;
        return 1;
    } else if (lead >= 0xc2 && lead <= 0xdf) {
        length = 2, lowest = 0x80, code_point = lead & 0x1f;
    } else if (lead >= 0xe0 && lead <= 0xef) {
        length = 3, lowest = 0x800, code_point = lead & 0x0f;
    } else if (lead >= 0xf0 && lead <= 0xf4) {
        length = 4, lowest = 0x10000, code_point = lead & 0x07;
    } else {
        return 0;
    }
    if (i + length > text.size()) return 0;
    for (std::size_t k = 1; k < length; ++k) {
        if ((byte(i + k) & 0xc0) != 0x80) return 0;
        code_point = (code_point << 6) | (byte(i + k) & 0x3f);
    }
    if (code_point < lowest || code_point > 0x10ffff || (code_point >= 0xd800 && code_point <= 0xdfff)) return 0;
    return length;
}

// The Unicode controls that reorder how text around them is shown (UAX #9): a name holding one can
// read as another name, or as a different extension, in a terminal, a listing or a page.
bool bidi_control(char32_t c) {
    return c == 0x061c || c == 0x200e || c == 0x200f || (c >= 0x202a && c <= 0x202e) || (c >= 0x2066 && c <= 0x2069);
}

} // namespace

std::optional<std::size_t> invalid_utf8_at(std::string_view text) {
    for (std::size_t i = 0; i < text.size();) {
        char32_t c;
        const std::size_t n = utf8_sequence(text, i, c);
        if (n == 0) return i;
        i += n;
    }
    return std::nullopt;
}

std::optional<std::string> name_problem(std::string_view name) {
    if (name.empty()) return "is empty";
    if (name == "." || name == "..") return fmt::format("is '{}', which names a folder, not a file", name);
    if (name.size() > kMaxNameBytes)
        return fmt::format("is {} bytes long; kdop names files after it and takes at most {}", name.size(),
                           kMaxNameBytes);
    for (std::size_t i = 0; i < name.size();) {
        char32_t c;
        const std::size_t n = utf8_sequence(name, i, c);
        if (n == 0)
            return fmt::format("is not valid UTF-8 (byte {}: \\x{:02x}), which JSON and HTML cannot hold", i,
                               static_cast<unsigned char>(name[i]));
        if (c == '/') return "holds a '/', which would make it a path";
        if (c < 0x20 || c == 0x7f) return fmt::format("holds a control byte (\\x{:02x})", std::uint32_t(c));
        if (c >= 0x80 && c < 0xa0) return fmt::format("holds a control character (U+{:04X})", std::uint32_t(c));
        if (bidi_control(c))
            return fmt::format("holds U+{:04X}, a bidirectional-text control that shows the name reordered",
                               std::uint32_t(c));
        i += n;
    }
    return std::nullopt;
}

} // namespace kdop
