// The image codecs through OpenImageIO: the functions of the table the module kdop_image_codecs.so
// gives (images/image_codecs.h, where each is described), compiled into that module alone.
#pragma once

#include "images/image_codecs.h"

namespace kdop::oiio {

Result<Image> read(const std::string& file, const ImageRead& read);
Result<glm::uvec2> read_size(const std::string& file, const std::string& name);
Result<void> write(const std::filesystem::path& temporary, const std::string& path, const Image& image,
                   std::span<const char* const> data_channels, FloatPrecision precision);
Result<void> check_writable(const std::string& path);
Result<void> draw_text(Image& image, std::span<const TextLine> lines);

} // namespace kdop::oiio
