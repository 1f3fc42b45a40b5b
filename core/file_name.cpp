#include "core/file_name.h"

#include "core/utf8.h"

#include <fmt/format.h>

namespace kdop {
namespace {

// The code point of the Unicode control at name[i] that would hide in a listing or reorder how the
// name is shown (a C1 control, or a bidirectional-text control of UAX #9: U+061C, U+200E, U+200F,
// U+202A to U+202E, U+2066 to U+2069), or 0. `name` is well-formed UTF-8, so these are read off
// their encodings.
char32_t hidden_control_at(std::string_view name, std::size_t i) {
    const auto byte = [&](std::size_t k) { return i + k < name.size() ? static_cast<unsigned char>(name[i + k]) : 0u; };
    const unsigned b0 = byte(0), b1 = byte(1), b2 = byte(2);
    if (b0 == 0xc2 && b1 >= 0x80 && b1 <= 0x9f) return b1;
    if (b0 == 0xd8 && b1 == 0x9c) return 0x061c;
    if (b0 == 0xe2 && b1 == 0x80 && (b2 == 0x8e || b2 == 0x8f || (b2 >= 0xaa && b2 <= 0xae))) return 0x2000 + b2 - 0x80;
    if (b0 == 0xe2 && b1 == 0x81 && b2 >= 0xa6 && b2 <= 0xa9) return 0x2040 + b2 - 0x80;
    return 0;
}

} // namespace

std::optional<std::string> name_problem(std::string_view name) {
    if (name.empty()) return "is empty";
    if (name == "." || name == "..") return fmt::format("is '{}', which names a folder, not a file", name);
    if (name.size() > kMaxNameBytes)
        return fmt::format("is {} bytes long; kdop names files after it and takes at most {}", name.size(),
                           kMaxNameBytes);
    if (auto at = first_non_utf8_byte(name))
        return fmt::format("is not valid UTF-8 (byte {}: \\x{:02x}), which JSON and HTML cannot hold", *at,
                           static_cast<unsigned char>(name[*at]));
    for (std::size_t i = 0; i < name.size(); ++i) {
        const auto c = static_cast<unsigned char>(name[i]);
        if (c == '/') return "holds a '/', which would make it a path";
        if (c < 0x20 || c == 0x7f) return fmt::format("holds a control byte (\\x{:02x})", c);
        if (const char32_t hidden = hidden_control_at(name, i))
            return fmt::format("holds U+{:04X}, a control character that hides in a listing or shows the name "
                               "reordered",
                               std::uint32_t(hidden));
    }
    return std::nullopt;
}

} // namespace kdop
