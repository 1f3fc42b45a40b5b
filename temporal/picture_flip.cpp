#include "temporal/picture_flip.h"

namespace kdop {

Result<std::vector<float>> PictureFlip::map(const Image& reference, const Image& test) const {
    if (range == ColorRange::ldr) return flip->ldr().error_map(reference, test);
    auto maps = flip->maps(reference, test, exposure);
    if (!maps) return std::unexpected(maps.error());
    return std::move(maps->error);
}

Image PictureFlip::shown(const Image& image) const {
    return range == ColorRange::hdr ? HdrFlip::tone_mapped(image, exposure.tone_mapper, 0.0f) : image;
}

} // namespace kdop
