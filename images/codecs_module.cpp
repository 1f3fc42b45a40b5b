// The module kdop_image_codecs.so: its one exported symbol gives the table of OpenImageIO's codecs
// (images/image_codecs.h) to an executable of the same build.
#include "images/oiio_codecs.h"

#include <string>

extern "C" __attribute__((visibility("default"))) const kdop::ImageCodecs* kdop_image_codecs(const char* build) {
    static const kdop::ImageCodecs codecs{
        .read = kdop::oiio::read,
        .read_size = kdop::oiio::read_size,
        .write = kdop::oiio::write,
        .check_writable = kdop::oiio::check_writable,
        .draw_text = kdop::oiio::draw_text,
    };
    static const std::string own = kdop::image_codecs_build();
    return build && own == build ? &codecs : nullptr;
}
