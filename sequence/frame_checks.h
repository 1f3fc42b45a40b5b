// Checks every reader of frame files makes (sequence.json's, an NSS capture's): where a file lies,
// and that the values read are finite.
#pragma once

#include "core/result.h"
#include "images/image.h"

#include <filesystem>
#include <string_view>

namespace kdop {

// Whether `path` is `folder` or lies inside it, both resolved already.
bool lies_inside(const std::filesystem::path& path, const std::filesystem::path& folder);

// Refuses a NaN or infinite value among the first `channels` of `image`, read from `file`, naming
// the pixel; `what` says what must be finite.
Result<void> check_finite(const Image& image, const std::filesystem::path& file, int channels, std::string_view what);

} // namespace kdop
