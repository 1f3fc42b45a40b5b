#include "core/file_name.h"

#include "core/utf8.h"

#include <fmt/format.h>

namespace kdop {

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
