// Whether text is well-formed UTF-8, the only text JSON can hold: nlohmann::json throws on any
// other byte when it writes a document, after all the work that made it. Names and file text that
// may reach JSON are checked with this where they are read, so the refusal names the file and line.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace kdop {

// The offset of the first byte of `text` that is not part of well-formed UTF-8 (The Unicode
// Standard, table 3-7: no overlong forms, no surrogates, nothing past U+10FFFF, no sequence cut
// short), or nothing where all of it is.
std::optional<std::size_t> first_non_utf8_byte(std::string_view text);

// The code point of the Unicode control character encoded at text[i] that a reader cannot see: a
// C1 control (U+0080 to U+009F) or a bidirectional-text control of UAX #9 (U+061C, U+200E, U+200F,
// U+202A to U+202E, U+2066 to U+2069), which shows the text around it reordered, so that
// "evil\u202egnp.exr" reads as "evilexe.png"; 0 where none starts there. Its encoding is 2 or 3
// bytes (hidden_control_bytes).
char32_t hidden_control_at(std::string_view text, std::size_t i);
std::size_t hidden_control_bytes(char32_t control);

// `text` as one line of UTF-8: every byte that is not part of well-formed UTF-8, and every control
// byte (tab aside), as the four characters \xNN; the rest, non-ASCII included, as it is. For text
// kdop writes into a file it reads back as UTF-8 lines (a fitted set's provenance, naming its input).
std::string utf8_line(std::string_view text);

} // namespace kdop
