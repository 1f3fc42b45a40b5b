// write_test_cases (texture_cases.h): apart from texture_cases.cpp because it writes through
// OpenImageIO (kdop_images), which the synthetic content does not need.
#include "images/image_io.h"
#include "images/texture_cases.h"

#include <fmt/format.h>

namespace kdop {

Result<std::size_t> write_test_cases(const std::vector<TestCase>& cases, const std::filesystem::path& dir) {
    std::vector<ImageFile> images;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const TestCase& c = cases[i];
        if (i == 0 || c.texture != cases[i - 1].texture) // a texture's first case: its image
            images.push_back({dir / (c.texture + ".exr"), &c.current});
        images.push_back({dir / fmt::format("{}-history-{}.exr", c.texture, to_string(c.model)), &c.history});
    }
    if (auto ok = write_images(images); !ok) return std::unexpected(ok.error());
    return images.size();
}

} // namespace kdop
