// A guard in front of OpenImageIO's JPEG reader. Debian 12's OpenImageIO (2.4) takes the size of
// an APP13 segment's IPTC block from the block's own 16-bit field, not from the segment, and reads
// that many bytes (JpgInput::jpeg_decode_iptc, decode_iptc_iim): a damaged or crafted file reads
// past the segment's end (found by kdop's image fuzzer under ASan; fixed upstream later). Until
// the library kdop builds with is fixed, kdop walks a JPEG's markers up to its scan itself and
// refuses an IPTC block that claims more than its segment holds, before the library sees the file.
// Written by hand because no library kdop uses reads JPEG markers without decoding them.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace kdop {

// Why the JPEG at `path` cannot be handed to OpenImageIO safely ("its APP13 segment's IPTC block
// claims 65535 bytes, and the segment holds 12"), or nothing: not a JPEG, or its APP13 segments
// are whole. Anything else wrong with the file is the decoder's to find.
std::optional<std::string> unsafe_jpeg_metadata(const std::filesystem::path& path);

} // namespace kdop
