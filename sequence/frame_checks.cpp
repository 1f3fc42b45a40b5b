#include "sequence/frame_checks.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace kdop {

bool lies_inside(const std::filesystem::path& path, const std::filesystem::path& folder) {
    return std::mismatch(folder.begin(), folder.end(), path.begin(), path.end()).first == folder.end();
}

Result<void> check_finite(const Image& image, const std::filesystem::path& file, int channels, std::string_view what) {
    for (std::uint32_t y = 0; y < image.height; ++y)
        for (std::uint32_t x = 0; x < image.width; ++x)
            for (int c = 0; c < channels; ++c)
                if (!std::isfinite(image.at(x, y)[c]))
                    return fail(fmt::format("{}: pixel ({}, {}) holds {} in channel {}; {} must be finite",
                                            file.string(), x, y, image.at(x, y)[c], c, what));
    return {};
}

} // namespace kdop
