#include "trail_picture.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

namespace kdop {
namespace {

constexpr int kLabelHeight = 22, kFontSize = 15, kGap = 4;
constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

} // namespace

Result<Image> trail_picture(std::span<const LabeledFrame> frames, const TrailCrop& crop, std::uint32_t columns) {
    if (frames.empty()) return fail("trail picture: no frames");
    const Image& first = *frames[0].frame;
    if (crop.scale == 0 || crop.width == 0 || crop.height == 0 || crop.x + crop.width > first.width ||
        crop.y + crop.height > first.height)
        return fail(fmt::format("trail picture: the crop {}x{} at ({}, {}) leaves the {}x{} frame", crop.width,
                                crop.height, crop.x, crop.y, first.width, first.height));
    const int w = int(crop.width * crop.scale), h = int(crop.height * crop.scale);
    const bool maps = std::any_of(frames.begin(), frames.end(), [](const LabeledFrame& f) { return f.error_map; });
    const int cols = int(std::min<std::size_t>(columns, frames.size()));
    const int rows = int((frames.size() + cols - 1) / cols);
    const int cell_w = w + kGap, cell_h = kLabelHeight + h * (maps ? 2 : 1) + kGap;

    OIIO::ImageBuf grid(OIIO::ImageSpec(cols * cell_w - kGap, rows * cell_h - kGap, 3, OIIO::TypeDesc::FLOAT));
    OIIO::ImageBufAlgo::zero(grid);
    // The crop of `image`, magnified, with its top left corner at (x0, y0) of the grid.
    auto place = [&](const Image& image, int x0, int y0) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const glm::vec4& c = image.at(crop.x + x / crop.scale, crop.y + y / crop.scale);
                const float rgb[3] = {c.r, c.g, c.b};
                grid.setpixel(x0 + x, y0 + y, rgb, 3);
            }
    };
    const std::string font = std::filesystem::exists(kFont) ? kFont : "";
    const float white[3] = {1, 1, 1};
    for (std::size_t i = 0; i < frames.size(); ++i) {
        for (const Image* image : {frames[i].frame, frames[i].error_map})
            if (image && (image->width != first.width || image->height != first.height))
                return fail("trail picture: frames of different sizes");
        const int x0 = int(i % cols) * cell_w, y0 = int(i / cols) * cell_h;
        place(*frames[i].frame, x0, y0 + kLabelHeight);
        if (frames[i].error_map) place(*frames[i].error_map, x0, y0 + kLabelHeight + h);
        if (!OIIO::ImageBufAlgo::render_text(grid, x0 + 4, y0 + kLabelHeight - 6, frames[i].label, kFontSize, font,
                                             white))
            return fail(
                fmt::format("trail picture: cannot draw the label \"{}\": {}", frames[i].label, grid.geterror()));
    }

    Image out(grid.spec().width, grid.spec().height);
    for (std::uint32_t y = 0; y < out.height; ++y)
        for (std::uint32_t x = 0; x < out.width; ++x) {
            float rgb[3];
            grid.getpixel(int(x), int(y), rgb, 3);
            out.at(x, y) = glm::vec4(rgb[0], rgb[1], rgb[2], 1.0f); // text is blended over [0, 1] frames
        }
    return out;
}

} // namespace kdop
