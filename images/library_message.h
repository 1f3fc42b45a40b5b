// OpenImageIO's error text made fit for one line of a message.
#pragma once

#include <string>
#include <string_view>

namespace kdop {

// An error from OpenImageIO (or the codec library under it) as one line of text: it may span lines
// ("PNG read error: ...\nPNG library error") and, from a damaged file, hold control bytes, which
// are shown as \xNN rather than sent to the terminal.
std::string library_message(std::string_view text);

} // namespace kdop
