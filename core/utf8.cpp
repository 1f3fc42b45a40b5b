#include "core/utf8.h"

#include <fmt/format.h>

#include <algorithm>

namespace kdop {

std::optional<std::size_t> first_non_utf8_byte(std::string_view text) {
    const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
    std::size_t i = 0;
    while (i < text.size()) {
        const unsigned char lead = byte(i);
        if (lead < 0x80) {
            ++i;
            continue;
        }
        // The sequence's length and the range of its second byte, which rules out overlong forms
        // (E0 and F0), surrogates (ED) and code points past U+10FFFF (F4) as table 3-7 does.
        std::size_t length = 0;
        unsigned char low = 0x80, high = 0xbf;
        if (lead >= 0xc2 && lead <= 0xdf) {
            length = 2;
        } else if (lead >= 0xe0 && lead <= 0xef) {
            length = 3;
            if (lead == 0xe0) low = 0xa0;
            if (lead == 0xed) high = 0x9f;
        } else if (lead >= 0xf0 && lead <= 0xf4) {
            length = 4;
            if (lead == 0xf0) low = 0x90;
            if (lead == 0xf4) high = 0x8f;
        } else {
            return i; // a continuation byte without a lead, C0, C1 or F5..FF
        }
        if (i + 1 >= text.size() || byte(i + 1) < low || byte(i + 1) > high) return i;
        for (std::size_t k = 2; k < length; ++k)
            if (i + k >= text.size() || byte(i + k) < 0x80 || byte(i + k) > 0xbf) return i;
        i += length;
    }
    return std::nullopt;
}

char32_t hidden_control_at(std::string_view text, std::size_t i) {
    const auto byte = [&](std::size_t k) { return i + k < text.size() ? static_cast<unsigned char>(text[i + k]) : 0u; };
    const unsigned b0 = byte(0), b1 = byte(1), b2 = byte(2);
    if (b0 == 0xc2 && b1 >= 0x80 && b1 <= 0x9f) return b1;
    if (b0 == 0xd8 && b1 == 0x9c) return 0x061c;
    if (b0 == 0xe2 && b1 == 0x80 && (b2 == 0x8e || b2 == 0x8f || (b2 >= 0xaa && b2 <= 0xae))) return 0x2000 + b2 - 0x80;
    if (b0 == 0xe2 && b1 == 0x81 && b2 >= 0xa6 && b2 <= 0xa9) return 0x2040 + b2 - 0x80;
    return 0;
}

std::size_t hidden_control_bytes(char32_t control) { return control < 0x800 ? 2 : 3; }

std::string utf8_line(std::string_view text) {
    std::string out;
    while (!text.empty()) {
        const std::size_t good = first_non_utf8_byte(text).value_or(text.size());
        for (char ch : text.substr(0, good)) {
            const unsigned char c = static_cast<unsigned char>(ch);
            if ((c < 0x20 && ch != '\t') || c == 0x7f)
                out += fmt::format("\\x{:02x}", c);
            else
                out += ch;
        }
        if (good < text.size()) out += fmt::format("\\x{:02x}", static_cast<unsigned char>(text[good]));
        text.remove_prefix(std::min(good + 1, text.size()));
    }
    return out;
}

} // namespace kdop
