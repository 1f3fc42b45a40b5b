#include "fit/frame_neighborhoods.h"

#include "generator/variant_spec.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

namespace kdop {

std::uint64_t neighborhood_bytes(std::uint64_t pixels, Neighborhood shape) {
    return pixels * (neighborhood_offsets(shape).size() * sizeof(glm::dvec3) + sizeof(std::uint32_t));
}

FrameNeighborhoods::FrameNeighborhoods(Neighborhoods held) {
    total_ = held.count();
    held_bytes_ = held.points.size() * sizeof(glm::dvec3) + held.repeats.size() * sizeof(std::uint32_t);
    frames_.push_back({"", held.count(), {}});
    held_.push_back(std::move(held));
    is_held_.push_back(true);
    share_.end = 1;
}

Result<FrameNeighborhoods> FrameNeighborhoods::gather(std::vector<FitFrame> frames, Neighborhood shape,
                                                      std::uint64_t budget, FrameShare share,
                                                      const std::function<void(std::size_t, const Image&)>& on_frame) {
    FrameNeighborhoods out;
    out.shape_ = shape;
    share.end = std::min(share.end, frames.size());
    out.share_ = std::move(share);
    out.held_.resize(frames.size());
    out.is_held_.assign(frames.size(), false);
    for (const FitFrame& frame : frames) out.total_ += frame.pixels;
    for (std::size_t i = out.share_.first; i < out.share_.end; ++i) {
        auto image = frames[i].load();
        if (!image) return std::unexpected(image.error());
        gather_neighborhoods({&*image, 1}, shape, out.scratch_);
        const std::uint64_t bytes =
            out.scratch_.points.size() * sizeof(glm::dvec3) + out.scratch_.repeats.size() * sizeof(std::uint32_t);
        // Held in frame order while the budget lasts: the first frames stay, the later ones are
        // read again on each pass.
        if (out.held_bytes_ + bytes <= budget && (i == out.share_.first || out.is_held_[i - 1])) {
            out.held_bytes_ += bytes;
            out.held_[i] = std::exchange(out.scratch_, {});
            out.held_[i].points.shrink_to_fit(); // the room repeats left unused
            out.is_held_[i] = true;
        }
        if (on_frame) on_frame(i, *image);
    }
    out.frames_ = std::move(frames);
    return out;
}

std::size_t FrameNeighborhoods::held_frames() const {
    return std::size_t(std::count(is_held_.begin(), is_held_.end(), true));
}

void FrameNeighborhoods::visit(const std::function<void(std::size_t, const Neighborhoods&)>& visit) const {
    for (std::size_t i = share_.first; i < std::min(share_.end, frames_.size()); ++i) {
        if (is_held_[i]) {
            visit(i, held_[i]);
            continue;
        }
        auto image = frames_[i].load();
        if (!image)
            throw FitInputError(
                fmt::format("{} (it was read on the first pass; has it changed since?)", image.error().message));
        gather_neighborhoods({&*image, 1}, shape_, scratch_);
        visit(i, scratch_);
    }
}

} // namespace kdop
