// The checks a reader makes on an image's header before it decodes a pixel, shared by the codecs'
// module (images/oiio_read.cpp) and the plain-PNG reader (images/png_read.cpp), so that both refuse
// a file in the same words.
#pragma once

#include "core/memory_budget.h"
#include "core/result.h"

#include <fmt/format.h>

#include <cstdint>
#include <string>

namespace kdop {

// A side beyond `max_side` (a device's maxImageDimension2D; 0 for no limit).
inline Result<void> check_max_side(const std::string& path, std::uint64_t width, std::uint64_t height,
                                   std::uint32_t max_side) {
    if (max_side && (width > max_side || height > max_side))
        return fail(fmt::format("{}: {}x{} is larger than the device allows: at most {} pixels on a side", path, width,
                                height, max_side));
    return {};
}

// The memory a whole read of a width x height image of `channels` channels takes: the image, and
// the decoded pixels of an 8- or 16-bit file (as much as a reader that holds the whole file's
// pixels takes besides: an interlaced PNG's).
inline std::uint64_t whole_read_bytes(std::uint32_t width, std::uint32_t height, int channels) {
    return image_bytes(width, height) + std::uint64_t(width) * height * std::uint64_t(channels) * 4;
}

} // namespace kdop
