#include "core/shown_text.h"

#include "core/utf8.h"

#include <fmt/format.h>

namespace kdop {

std::string shown_text(std::string_view text, std::size_t limit) {
    std::string out;
    for (std::size_t i = 0; i < text.size() && i < limit; ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c < 0x20 || c >= 0x7f)
            out += fmt::format("\\x{:02x}", c);
        else
            out += text[i];
    }
    if (text.size() > limit) out += fmt::format("... ({} bytes in all)", text.size());
    return out;
}

namespace {

std::string printable_text(std::string_view text, bool keep_layout) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        const bool layout = keep_layout && (c == '\n' || c == '\t');
        if ((c < 0x20 && !layout) || c == 0x7f) {
            out += fmt::format("\\x{:02x}", c);
        } else if (const char32_t hidden = hidden_control_at(text, i)) {
            const std::size_t bytes = hidden_control_bytes(hidden);
            for (std::size_t k = 0; k < bytes; ++k)
                out += fmt::format("\\x{:02x}", static_cast<unsigned char>(text[i + k]));
            i += bytes - 1;
        } else {
            out += text[i];
        }
    }
    return out;
}

} // namespace

std::string terminal_text(std::string_view text) { return printable_text(text, true); }

std::string one_line_text(std::string_view text) { return printable_text(text, false); }

} // namespace kdop
