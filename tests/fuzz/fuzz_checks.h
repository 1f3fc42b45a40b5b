// What the fuzz targets check, shared: a violated property aborts (libFuzzer then reports the
// input), and text kdop shows must not carry control bytes to the terminal.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace kdop::fuzz {

// Aborts with `what` and the offending `text` unless `condition` holds.
inline void require(bool condition, const char* what, const std::string& text) {
    if (condition) return;
    std::fprintf(stderr, "fuzz check failed: %s\n%s\n", what, text.c_str());
    std::abort();
}

// Whether `text` holds a control byte other than a tab (and, where allowed, a line break).
inline bool has_control_bytes(std::string_view text, bool allow_newlines = false) {
    for (char ch : text) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if ((c < 0x20 && c != '\t' && !(allow_newlines && c == '\n')) || c == 0x7f) return true;
    }
    return false;
}

// Aborts unless `message`, a refusal of what a reader found in `folder`, names `file` or a file of
// `folder` (it starts with the folder's path), echoes no control byte and stays short.
inline void require_refusal_message(const std::string& message, std::string_view file, const std::string& folder) {
    require(message.find(file) != std::string::npos || message.find(folder) == 0, "an error that names no file",
            message);
    require(!has_control_bytes(message, false), "an error that echoes control bytes", message);
    require(message.size() < 2000, "an error that repeats the input whole", message);
}

} // namespace kdop::fuzz
