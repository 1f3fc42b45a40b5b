#include "sequence/frame_source.h"

#include <fmt/format.h>

#include <algorithm>

namespace kdop {

Result<std::vector<glm::vec2>> FrameSource::output_motion(std::size_t index) const {
    return fail(fmt::format("{}: kdop has no motion at the output size for this source", frame_label(index)));
}

bool SequenceFrames::has_depth() const {
    return depth_ &&
           std::all_of(s_.frames.begin(), s_.frames.end(), [](const SequenceFrame& f) { return !f.depth.empty(); });
}

bool SequenceFrames::has_reference() const {
    return std::all_of(s_.frames.begin(), s_.frames.end(), [](const SequenceFrame& f) { return !f.reference.empty(); });
}

std::string SequenceFrames::frame_label(std::size_t index) const {
    return fmt::format("{} (frame {})", s_.frames[index].color.string(), index);
}

} // namespace kdop
