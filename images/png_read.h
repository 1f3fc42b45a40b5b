// Plain PNGs read by libpng alone: the common LDR input (a `kdop flip` pair, a texture) is decoded
// without loading the codecs' module (images/image_codecs.h), whose 260 libraries cost 0.17 CPU s
// to load, a third of a 1080p `kdop flip` pair.
#pragma once

#include "images/image_codecs.h"

#include <optional>

namespace kdop {

// The image in `file` where it is a plain PNG (by its name's extension and its signature): 8 bits
// a channel, RGB or RGBA, not interlaced, and no chunk that says its values are other than
// sRGB-encoded color as stored (iCCP, sBIT, tRNS, PLTE; gAMA and cHRM but sRGB's own beside an
// sRGB chunk, as kdop's PNGs hold them; text whose keyword starts "oiio:", which OpenImageIO takes
// as the image's attributes, but "oiio:ColorSpace" saying sRGB, as kdop's PNGs do), read whole
// (`read.corner` 0x0). Its pixels are
// those the codecs give for the same file, bit for bit (tests/image_io_test.cpp compares them),
// and it is refused in the codecs' words (images/header_checks.h). Nothing for any other file, or
// one libpng cannot decode: the codecs then read it, or say what is wrong with it.
std::optional<Result<Image>> read_plain_png(const std::string& file, const ImageRead& read);

} // namespace kdop
