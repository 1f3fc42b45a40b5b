// Which of OpenImageIO's readers decode an image a row at a time, so that reading its top rows
// costs those rows alone: what lets a background far larger than the frame it is tiled or cropped
// to be read for the corner it gives (images/image_io.h, read_image_corner). The others (an
// interlaced PNG, TGA, GIF, a TIFF of one strip, a progressive JPEG, tiled EXR) hold the whole
// image, or its coefficients, on the first row asked for.
#pragma once

#include <OpenImageIO/imageio.h>

#include <filesystem>

namespace kdop {

// Whether `in`, open on `file`, decodes row by row: a PNG that is not interlaced (Adam7 holds the
// whole image; its IHDR says which, and OpenImageIO does not), or a scanline OpenEXR file.
bool decodes_by_rows(const OIIO::ImageInput& in, const std::filesystem::path& file);

} // namespace kdop
