// Text over an image through OpenImageIO's FreeType rendering (images/image_codecs.h, draw_text).
#include "images/oiio_codecs.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>

#include <filesystem>

namespace kdop::oiio {
namespace {

constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// The largest font size from `size` down to 8 at which `text` fits in `width` pixels.
int fitting_font_size(const std::string& text, int size, int width, const std::string& font) {
    for (; size > 8; --size)
        if (OIIO::ImageBufAlgo::text_size(text, size, font).width() <= width) break;
    return size;
}

} // namespace

Result<void> draw_text(Image& image, std::span<const TextLine> lines) {
    // The image's RGB as OpenImageIO's buffer, in place: three float channels a vec4 apart, so the
    // text changes neither alpha nor any value where no glyph is.
    OIIO::ImageBuf rgb(OIIO::ImageSpec(int(image.width), int(image.height), 3, OIIO::TypeDesc::FLOAT),
                       image.pixels.data(), sizeof(glm::vec4));
    const std::string font = std::filesystem::exists(kFont) ? kFont : "";
    const float white[3] = {1, 1, 1};
    for (const TextLine& line : lines) {
        const int size = line.max_width > 0 ? fitting_font_size(line.text, line.size, line.max_width, font) : line.size;
        if (!OIIO::ImageBufAlgo::render_text(rgb, line.x, line.y, line.text, size, font, white))
            return fail(fmt::format("cannot draw the text \"{}\": {}", line.text, rgb.geterror()));
    }
    return {};
}

} // namespace kdop::oiio
