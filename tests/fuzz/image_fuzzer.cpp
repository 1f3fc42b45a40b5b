// libFuzzer target: any bytes as an image file, through kdop's read_image (OpenImageIO picks the
// reader from the content). Whatever is refused must be refused with a message that names the file
// and holds no raw control bytes; whatever is read must be within the side limit it was given, its
// corner read alone (read_image_corner) must be the same pixels, and it must write to EXR and read
// back bit for bit (NaN and infinity included), so nothing read is something kdop cannot keep. Any
// violation aborts, which libFuzzer reports; so does any sanitizer report or an allocation beyond
// libFuzzer's limit (a header claiming more than it holds).
// The corpus: 4x4 images in each format kdop reads (oiiotool --pattern ... -d uint8|uint16|half|float),
// a 5x4 interlaced PNG (read whole, where a plain one is read by rows) and the two oversized headers
// of tests/data.
#include "images/image_io.h"
#include "tests/fuzz/fuzz_checks.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <unistd.h>

namespace {

using kdop::fuzz::has_control_bytes;
using kdop::fuzz::require;

// A device's side limit, small enough that any image within it decodes in libFuzzer's memory limit.
constexpr std::uint32_t kMaxSide = 1024;

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b)); }

// A folder of this process's own, removed at exit: the input is written there under a name with no
// extension, so the reader is chosen by what the bytes are. The process id is padded so the path,
// which the messages quote, has the same length in every run: the same inputs from the same seed.
struct Scratch {
    std::filesystem::path folder =
        std::filesystem::temp_directory_path() / fmt::format("kdop-image-fuzzer-{:010}", ::getpid());
    Scratch() { std::filesystem::create_directories(folder); }
    ~Scratch() { std::filesystem::remove_all(folder); }
};

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const Scratch scratch;
    const std::string input = (scratch.folder / "input").string();
    std::ofstream(input, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), size);

    auto image = kdop::read_image(input, kMaxSide);
    if (!image) {
        const std::string& message = image.error().message;
        require(message.rfind(input, 0) == 0, "an error that does not name the file", message);
        require(!has_control_bytes(message), "an error that echoes control bytes", message);
        return 0;
    }
    const std::string shape = std::to_string(image->width) + "x" + std::to_string(image->height);
    require(image->width > 0 && image->height > 0 && image->width <= kMaxSide && image->height <= kMaxSide,
            "an image read beyond the side limit", shape);
    require(image->pixels.size() == std::size_t(image->width) * image->height, "pixels that do not fill the image",
            shape);

    // The corner a tiled background takes (read_image_corner, read by rows where the format allows):
    // only of an image the whole read took, so within the side limit; the same pixels, bit for bit.
    const std::uint32_t corner_width = image->width / 2 + 1, corner_height = image->height / 3 + 1;
    auto corner = kdop::read_image_corner(input, corner_width, corner_height);
    require(corner.has_value(), "a corner that cannot be read of an image that can",
            corner ? shape : corner.error().message);
    require(corner->width == corner_width && corner->height == corner_height, "a corner of another shape", shape);
    for (std::uint32_t y = 0; y < corner_height; ++y)
        for (std::uint32_t x = 0; x < corner_width; ++x)
            for (int c = 0; c < 4; ++c)
                require(same_bits(corner->at(x, y)[c], image->at(x, y)[c]), "a corner with other values", shape);

    const std::string copy = (scratch.folder / "copy.exr").string();
    auto written = kdop::write_image(copy, *image);
    require(written.has_value(), "an image read that cannot be written as EXR",
            written ? shape : written.error().message);
    auto back = kdop::read_image(copy);
    require(back.has_value(), "an EXR written that cannot be read", back ? shape : back.error().message);
    require(back->width == image->width && back->height == image->height, "an EXR read back in another shape", shape);
    for (std::size_t i = 0; i < image->pixels.size(); ++i)
        for (int c = 0; c < 4; ++c)
            require(same_bits(back->pixels[i][c], image->pixels[i][c]), "an EXR read back with other values", shape);
    return 0;
}
