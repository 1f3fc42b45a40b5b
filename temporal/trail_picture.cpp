#include "temporal/trail_picture.h"

#include "images/image_codecs.h"

#include <fmt/format.h>

#include <algorithm>

namespace kdop {
namespace {

constexpr int kLabelHeight = 22, kNoteHeight = 18, kFontSize = 15, kNoteFontSize = 12, kGap = 4;
constexpr int kScaleHeight = 40, kBarHeight = 12, kBarWidth = 320;

// Whether `crop` lies inside a width x height frame.
Result<void> check_crop(const TrailCrop& crop, std::uint32_t width, std::uint32_t height) {
    if (crop.scale == 0 || crop.width == 0 || crop.height == 0 || crop.x + crop.width > width ||
        crop.y + crop.height > height)
        return fail(fmt::format("trail picture: the crop {}x{} at ({}, {}) leaves the {}x{} frame", crop.width,
                                crop.height, crop.x, crop.y, width, height));
    return {};
}

} // namespace

Result<Image> crop_of(const Image& frame, const TrailCrop& crop) {
    if (auto ok = check_crop(crop, frame.width, frame.height); !ok) return std::unexpected(ok.error());
    Image part(crop.width, crop.height);
    for (std::uint32_t y = 0; y < crop.height; ++y)
        for (std::uint32_t x = 0; x < crop.width; ++x) part.at(x, y) = frame.at(crop.x + x, crop.y + y);
    return part;
}

Result<std::vector<float>> crop_of(std::span<const float> map, std::uint32_t width, std::uint32_t height,
                                   const TrailCrop& crop) {
    if (auto ok = check_crop(crop, width, height); !ok) return std::unexpected(ok.error());
    if (map.size() != std::size_t(width) * height) return fail("trail picture: a map of another size than its frame");
    std::vector<float> part;
    part.reserve(std::size_t(crop.width) * crop.height);
    for (std::uint32_t y = 0; y < crop.height; ++y)
        for (std::uint32_t x = 0; x < crop.width; ++x)
            part.push_back(map[std::size_t(crop.y + y) * width + crop.x + x]);
    return part;
}

Result<Image> trail_picture(std::span<const LabeledFrame> frames, const TrailCrop& crop, std::uint32_t columns,
                            const ColorScale* scale) {
    if (frames.empty()) return fail("trail picture: no frames");
    const Image& first = *frames[0].frame;
    if (auto ok = check_crop(crop, first.width, first.height); !ok) return std::unexpected(ok.error());
    const int w = int(crop.width * crop.scale), h = int(crop.height * crop.scale);
    const bool maps = std::any_of(frames.begin(), frames.end(), [](const LabeledFrame& f) { return f.error_map; });
    const bool notes = std::any_of(frames.begin(), frames.end(), [](const LabeledFrame& f) { return !f.note.empty(); });
    const int cols = int(std::min<std::size_t>(columns, frames.size()));
    const int rows = int((frames.size() + cols - 1) / cols);
    const int note_h = notes ? kNoteHeight : 0;
    const int cell_w = w + kGap, cell_h = kLabelHeight + h * (maps ? 2 : 1) + note_h + kGap;
    const int grid_w = cols * cell_w - kGap, grid_h = rows * cell_h - kGap;

    Image grid(std::uint32_t(grid_w), std::uint32_t(grid_h + (scale ? kScaleHeight : 0))); // black, opaque
    // The crop of `image`, magnified, with its top left corner at (x0, y0) of the grid.
    auto place = [&](const Image& image, int x0, int y0) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const glm::vec4& c = image.at(crop.x + x / crop.scale, crop.y + y / crop.scale);
                grid.at(std::uint32_t(x0 + x), std::uint32_t(y0 + y)) = glm::vec4(c.r, c.g, c.b, 1.0f);
            }
    };
    // The labels and notes, drawn once the crops are placed (each in a strip of its own cell).
    std::vector<TextLine> lines;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        for (const Image* image : {frames[i].frame, frames[i].error_map})
            if (image && (image->width != first.width || image->height != first.height))
                return fail("trail picture: frames of different sizes");
        const int x0 = int(i % cols) * cell_w, y0 = int(i / cols) * cell_h;
        place(*frames[i].frame, x0, y0 + kLabelHeight);
        if (frames[i].error_map) place(*frames[i].error_map, x0, y0 + kLabelHeight + h);
        lines.push_back({x0 + 3, y0 + kLabelHeight - 6, frames[i].label, kFontSize, w - 6});
        if (!frames[i].note.empty())
            lines.push_back({x0 + 3, y0 + kLabelHeight + h * (maps ? 2 : 1) + kNoteHeight - 5, frames[i].note,
                             kNoteFontSize, w - 6});
    }
    if (scale && scale->bar->width > 0) {
        const int bar_w = std::min(kBarWidth, grid_w - 60), x0 = 20, y0 = grid_h + 8;
        for (int y = 0; y < kBarHeight; ++y)
            for (int x = 0; x < bar_w; ++x) {
                const glm::vec4& c =
                    scale->bar->at(std::uint32_t(x * (scale->bar->width - 1) / std::max(bar_w - 1, 1)), 0);
                grid.at(std::uint32_t(x0 + x), std::uint32_t(y0 + y)) = glm::vec4(c.r, c.g, c.b, 1.0f);
            }
        const int baseline = y0 + kBarHeight + 14;
        lines.push_back({x0 - 4, baseline, "0", kNoteFontSize});
        lines.push_back({x0 + bar_w - 4, baseline, "1", kNoteFontSize});
        lines.push_back({x0 + bar_w + 14, y0 + kBarHeight, scale->caption, kNoteFontSize, grid_w - bar_w - x0 - 18});
    }
    // Text is blended over [0, 1] frames; alpha stays 1.
    if (auto ok = draw_text(grid, lines); !ok) return fail("trail picture: " + ok.error().message);
    return grid;
}

} // namespace kdop
