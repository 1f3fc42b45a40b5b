#include "temporal/picture_flip.h"

namespace kdop {
namespace {

// The store's slots a picture's pair takes: those of a measurement's truth and first output,
// which is done when pictures are made.
constexpr std::size_t kReferenceSlot = 0, kTestSlot = 1;

} // namespace

Result<std::vector<float>> PictureFlip::map(const Image& reference, const Image& test, bool same_reference) {
    OutputStore& store = flip_->store();
    if (!same_reference || !reference_) reference_ = store.put(kReferenceSlot, reference);
    auto figure = flip_->evaluate(reference_, store.put(kTestSlot, test), range_, true);
    if (!figure) return std::unexpected(figure.error());
    return std::move(figure->map);
}

Image PictureFlip::shown(const Image& image) const {
    return range_ == ColorRange::hdr ? HdrFlip::tone_mapped(image, flip_->exposures().tone_mapper, 0.0f) : image;
}

} // namespace kdop
