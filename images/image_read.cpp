// Reading images: the checks before a file is handed to the codecs (images/image_codecs.h), which
// decode it in their module, or a plain PNG decoded here (images/png_read.h).
#include "images/image_io.h"

#include "core/input_files.h"
#include "core/read_file.h"
#include "images/image_codecs.h"
#include "images/jpeg_guard.h"
#include "images/png_read.h"

#include <fmt/format.h>

#include <cmath>

namespace kdop {

namespace {

// Why `file` must not be opened by the codecs, with messages naming `path`, or nothing.
Result<void> check_before_opening(const std::string& file, const std::string& path) {
    // A device (/dev/zero) or a pipe would be read without end.
    if (auto why = not_a_readable_file(file)) return fail(fmt::format("{}: cannot read image: {}", path, *why));
    if (auto why = unsafe_jpeg_metadata(file)) return fail(fmt::format("{}: cannot read image: {}", path, *why));
    return {};
}

Result<Image> read_checked(const std::string& file, const ImageRead& read) {
    const std::string& path = read.name.empty() ? file : read.name; // what messages name
    if (auto ok = check_before_opening(file, path); !ok) return std::unexpected(ok.error());
    // Noted as the file it is, by its own name: an output that would replace it is refused naming
    // that, not the /proc/self/fd path it was read through.
    note_input(file, path);
    if (auto plain = read_plain_png(file, read)) return std::move(*plain);
    auto codecs = image_codecs();
    if (!codecs) return std::unexpected(codecs.error());
    return (*codecs)->read(file, read);
}

} // namespace

std::optional<InputSpace> parse_input_space(std::string_view text) {
    if (text == "file") return InputSpace::from_file;
    if (text == "linear") return InputSpace::linear;
    if (text == "srgb") return InputSpace::srgb;
    return std::nullopt;
}

Result<Image> read_image(const std::string& path, std::uint32_t max_side, InputSpace space, const std::string& name) {
    return read_checked(path, {.max_side = max_side, .space = space, .needed = 3, .name = name});
}

Result<Image> read_image_corner(const std::string& path, std::uint32_t width, std::uint32_t height, InputSpace space) {
    return read_checked(path, {.space = space, .needed = 3, .name = {}, .corner = {width, height}});
}

Result<glm::uvec2> read_image_size(const std::string& path, const std::string& name) {
    if (auto ok = check_before_opening(path, name.empty() ? path : name); !ok) return std::unexpected(ok.error());
    auto codecs = image_codecs();
    if (!codecs) return std::unexpected(codecs.error());
    return (*codecs)->read_size(path, name);
}

Result<Image> read_data_image(const std::string& path, int channels, const std::string& name) {
    return read_checked(path, {.space = InputSpace::linear, .needed = channels, .name = name});
}

Result<Image> read_finite_image(const std::string& path, std::string_view why, InputSpace space) {
    auto image = read_image(path, 0, space);
    if (!image) return image;
    for (std::uint32_t y = 0; y < image->height; ++y)
        for (std::uint32_t x = 0; x < image->width; ++x) {
            const glm::vec4& p = image->at(x, y);
            if (!std::isfinite(p.r) || !std::isfinite(p.g) || !std::isfinite(p.b))
                return fail(
                    fmt::format("{}: pixel ({}, {}) is not finite ({}, {}, {}); {}", path, x, y, p.r, p.g, p.b, why));
        }
    return image;
}

} // namespace kdop
