#include "images/row_reader.h"

#include <array>
#include <cstring>
#include <fstream>
#include <string_view>

namespace kdop {
namespace {

// Whether the PNG at `file` says in its IHDR (the first chunk, at a fixed place) that it is not
// interlaced; false when that cannot be read.
bool png_not_interlaced(const std::filesystem::path& file) {
    // The signature (8 bytes), the chunk's length (4) and type (4), width, height (4 each), bit
    // depth, color type, compression, filter, interlace (1 each).
    std::array<char, 29> header{};
    std::ifstream in(file, std::ios::binary);
    if (!in.read(header.data(), header.size())) return false;
    return std::memcmp(header.data(), "\x89PNG\r\n\x1a\n", 8) == 0 && std::memcmp(header.data() + 12, "IHDR", 4) == 0 &&
           header[28] == 0;
}

} // namespace

bool decodes_by_rows(const OIIO::ImageInput& in, const std::filesystem::path& file) {
    const std::string_view format = in.format_name();
    const OIIO::ImageSpec& spec = in.spec();
    if (spec.tile_width != 0 || spec.deep) return false;
    if (format == "openexr") return true;
    return format == "png" && png_not_interlaced(file);
}

} // namespace kdop
