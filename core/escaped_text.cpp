#include "core/escaped_text.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstring>

namespace kdop {
namespace {

bool is_control(unsigned char c) { return c < 0x20 || c == 0x7f; }

std::string hex(unsigned char c) { return fmt::format("\\x{:02x}", c); }

} // namespace

std::string cpp_string_literal(std::string_view text) {
    std::string out = "\"";
    for (char ch : text) {
        const unsigned char c = static_cast<unsigned char>(ch);
        switch (ch) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\t': out += "\\t"; break;
        case '?': out += "\\?"; break;
        default:
            if (is_control(c) || c >= 0x80)
                out += fmt::format("\\{:03o}", c);
            else
                out += ch;
        }
    }
    return out + "\"";
}

std::string line_comment_text(std::string_view text) {
    std::string out;
    for (char ch : text) {
        const unsigned char c = static_cast<unsigned char>(ch);
        out += is_control(c) || c >= 0x80 ? hex(c) : std::string(1, ch);
    }
    if (out.ends_with('\\')) out.replace(out.size() - 1, 1, hex('\\'));
    return out;
}

std::string markdown_text(std::string_view text) {
    // The punctuation that starts or ends markup inside a line: an escape, code, emphasis, a link
    // or image, an HTML tag or entity, strikethrough, a table cell. The rest ('-', '.', '#', '+')
    // means something only at a line's start, where kdop never puts a name.
    constexpr const char* kMarkup = "\\`*_[]<>|&~";
    std::string out;
    for (char ch : text) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (is_control(c))
            out += hex(c);
        else if (ch != '\0' && std::strchr(kMarkup, ch))
            out += std::string("\\") + ch;
        else
            out += ch;
    }
    return out;
}

std::string markdown_destination(std::string_view path) {
    // A plain path (kdop's own file names) stays as it is; anything else goes in angle brackets.
    const bool plain = !path.empty() && std::all_of(path.begin(), path.end(), [](char ch) {
        return std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '_' || ch == '-' || ch == '/';
    });
    if (plain) return std::string(path);
    std::string out = "<";
    for (char ch : path) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (is_control(c))
            out += fmt::format("%{:02X}", c);
        else if (ch == '<' || ch == '>' || ch == '\\')
            out += std::string("\\") + ch;
        else
            out += ch;
    }
    return out + ">";
}

std::string markdown_code(std::string_view text) {
    std::string shown;
    std::size_t run = 0, longest = 0;
    for (char ch : text) {
        const unsigned char c = static_cast<unsigned char>(ch);
        run = ch == '`' ? run + 1 : 0;
        longest = std::max(longest, run);
        shown += is_control(c) ? hex(c) : std::string(1, ch);
    }
    const std::string fence(longest + 1, '`');
    // A space inside the fence where the code starts or ends with a backtick (CommonMark strips one).
    const bool pad = shown.starts_with('`') || shown.ends_with('`');
    return fence + (pad ? " " : "") + shown + (pad ? " " : "") + fence;
}

std::string html_text(std::string_view text) {
    std::string shown;
    for (char ch : text) {
        const unsigned char c = static_cast<unsigned char>(ch);
        switch (ch) {
        case '&': shown += "&amp;"; break;
        case '<': shown += "&lt;"; break;
        case '>': shown += "&gt;"; break;
        case '"': shown += "&quot;"; break;
        case '\'': shown += "&#39;"; break;
        default: shown += is_control(c) ? hex(c) : std::string(1, ch);
        }
    }
    return shown;
}

std::string url_path(std::string_view path) {
    std::string url;
    for (char ch : path) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if ((c < 0x80 && std::isalnum(c)) || std::string_view("-._~/").find(ch) != std::string_view::npos)
            url += ch;
        else
            url += fmt::format("%{:02X}", c);
    }
    return url;
}

} // namespace kdop
