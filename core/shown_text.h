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

} // namespace kdop
