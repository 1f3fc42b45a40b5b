// Text from a file or a command line as an error message shows it: bytes outside printable ASCII
// (control bytes, a byte-order mark, any invisible character that would make a bad name look
// right) as \xNN, and anything past `limit` bytes cut, saying how long it was. A 50 MB line in a
// manifest gives a message of a line, not of 50 MB.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace kdop {

std::string shown_text(std::string_view text, std::size_t limit = 120);

// Text a kdop program prints (an error naming a file, "wrote <path>") as a terminal may receive it:
// control bytes as \xNN, so a file named "\x1b[31mRED.exr" cannot recolor or rewrite the terminal
// and a NUL cannot cut the line, and the invisible Unicode controls (core/utf8.h, U+202E that shows
// a name reordered) as the \xNN of their bytes; line breaks and tabs (the layout of multi-line
// messages) and every other byte, UTF-8 included, as they are.
std::string terminal_text(std::string_view text);

// The same for text that must stay one line (a progress line, which a log keeps one per step): line
// breaks and tabs as \xNN too, so a name cannot forge a line of its own.
std::string one_line_text(std::string_view text);

} // namespace kdop
