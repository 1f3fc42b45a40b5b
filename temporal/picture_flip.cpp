#include "temporal/picture_flip.h"

namespace kdop {

Result<std::vector<float>> PictureFlip::map(const Image& reference, const Image& test, bool same_reference) const {
    auto figure = flip(reference, test, range, true, same_reference);
    if (!figure) return std::unexpected(figure.error());
    return std::move(figure->map);
}

Image PictureFlip::shown(const Image& image) const {
    return range == ColorRange::hdr ? HdrFlip::tone_mapped(image, exposure.tone_mapper, 0.0f) : image;
}

} // namespace kdop
