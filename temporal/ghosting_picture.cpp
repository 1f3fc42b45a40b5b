#include "temporal/ghosting_picture.h"

#include "flip/magma.h"
#include "temporal/trail_picture.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace kdop {

// ghosting-<scene>.png
std::string ghosting_picture_name(const std::string& scene) { return fmt::format("ghosting-{}.png", scene); }

PictureFrames frames_in_memory(std::vector<std::shared_ptr<const Image>> frames) {
    const std::size_t count = frames.size();
    return {count,
            [frames = std::move(frames)](std::size_t v) -> Result<std::shared_ptr<const Image>> { return frames[v]; }};
}

Result<std::vector<std::vector<float>>> ghosting_maps(PictureFlip& flip, const Image& truth,
                                                      const PictureFrames& frames) {
    std::vector<std::vector<float>> maps;
    for (std::size_t v = 0; v < frames.count; ++v) {
        auto frame = frames.frame(v);
        if (!frame) return std::unexpected(frame.error());
        auto map = flip.map(truth, **frame, !maps.empty());
        if (!map) return std::unexpected(map.error());
        maps.push_back(std::move(*map));
    }
    return maps;
}

Result<void> add_ghosting_picture(StagedImages& outputs, const PictureFrame& shown, const std::string& truth_name,
                                  std::shared_ptr<const Image> truth, const std::vector<VariantKey>& keys,
                                  const PictureFrames& trails, const std::vector<std::vector<float>>& errors,
                                  const std::vector<double>& ghosting, const PictureFlip& flip) {
    const std::uint32_t width = truth->width, height = truth->height;
    // As data, the frames as they are; to look at, as the picture shows them (HDR tone mapped).
    auto add_frame = [&](const std::string& stem, const Image& image) -> Result<void> {
        if (auto ok = outputs.add(fmt::format("frames/{}/{}.exr", shown.source, stem), image); !ok) return ok;
        return outputs.add(fmt::format("frames/{}/{}.png", shown.source, stem),
                           flip.range() == ColorRange::ldr ? image : flip.shown(image));
    };
    // The picture shows the crop alone: its looks and maps are made of the crop's pixels (of 12
    // variants at 1080p, whole ones held 0.8 GB).
    std::vector<Image> maps, looks;
    maps.reserve(trails.count); // the picture points into both
    looks.reserve(trails.count + 1);
    auto look = [&](const Image& frame) -> Result<void> {
        auto part = crop_of(frame, shown.crop);
        if (!part) return std::unexpected(part.error());
        looks.push_back(flip.shown(*part));
        return {};
    };
    if (auto ok = look(*truth); !ok) return ok;
    std::vector<LabeledFrame> labeled{{fmt::format("{}, frame {}", truth_name, shown.index), &looks.back()}};
    if (auto ok = add_frame(truth_name, *truth); !ok) return ok;
    for (std::size_t v = 0; v < keys.size(); ++v) {
        const std::vector<float>& error = errors[v];
        auto part = crop_of(error, width, height, shown.crop);
        if (!part) return std::unexpected(part.error());
        maps.push_back(flip::magma_image(*part, shown.crop.width, shown.crop.height));
        auto trail = trails.frame(v);
        if (!trail) return std::unexpected(trail.error());
        if (auto ok = look(**trail); !ok) return ok;
        if (auto ok = add_frame(keys[v].name(), **trail); !ok) return ok;
        labeled.push_back({keys[v].name(), &looks.back(), &maps.back(),
                           fmt::format("ghosting {:.4f} | frame {:.4f}", ghosting[v], mean_error(error))});
    }
    std::vector<float> ramp(256);
    for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = float(i) / float(ramp.size() - 1);
    const Image bar = flip::magma_image(ramp, std::uint32_t(ramp.size()), 1);
    const std::string caption =
        fmt::format("{} against the {}{}", flip.name(), truth_name == "aliased" ? "aliased frame" : truth_name,
                    flip.range() == ColorRange::hdr ? " (frames tone mapped)" : "");
    const ColorScale scale{&bar, caption};
    const TrailCrop whole_part{0, 0, shown.crop.width, shown.crop.height, shown.crop.scale};
    auto picture = trail_picture(labeled, whole_part, 4, &scale);
    if (!picture) return std::unexpected(picture.error());
    return outputs.add(ghosting_picture_name(shown.source), *picture);
}

Result<void> PictureFrameChooser::offer(const MeasuredFrame& frame) {
    double low = INFINITY, high = -INFINITY;
    for (const FrameFigures& f : frame.figures)
        low = std::min(low, f.value(kGhosting)), high = std::max(high, f.value(kGhosting));
    const double spread = frame.figures.size() == 1 ? high : high - low;
    if (fixed_ ? frame.index != *fixed_ : !(spread > spread_))
        return {}; // NaN (no ghosting measured) never wins; the earliest of equals stays
    auto outputs = frame.outputs();
    if (!outputs) return std::unexpected(outputs.error());
    if (!scratch_) scratch_ = std::make_unique<ScratchDirectory>("kdop-picture");
    if (scratch_->path.empty())
        return fail("cannot create a scratch folder for the picture's frame (is TMPDIR writable?)");
    for (std::size_t v = 0; v < outputs->size(); ++v)
        if (auto ok = write_raw(scratch_->path / std::to_string(v), *(*outputs)[v]); !ok) return ok;
    spread_ = spread;
    index_ = frame.index;
    outputs_ = outputs->size();
    if (!outputs->empty()) width_ = outputs->front()->width, height_ = outputs->front()->height;
    return {};
}

PictureFrames PictureFrameChooser::outputs() const {
    return {outputs_, [this](std::size_t v) -> Result<std::shared_ptr<const Image>> {
                auto image = read_raw_image(scratch_->path / std::to_string(v), width_, height_);
                if (!image) return std::unexpected(image.error());
                return std::make_shared<const Image>(std::move(*image));
            }};
}

TrailCrop disagreement_crop(const std::vector<std::vector<float>>& maps, std::uint32_t width, std::uint32_t height) {
    std::size_t most = 0;
    float largest = -1;
    for (std::size_t p = 0; p < std::size_t(width) * height; ++p) {
        float low = INFINITY, high = -INFINITY;
        for (const std::vector<float>& map : maps) low = std::min(low, map[p]), high = std::max(high, map[p]);
        const float difference = maps.size() == 1 ? high : high - low;
        if (difference > largest) largest = difference, most = p;
    }
    const std::uint32_t w = std::min(width, 320u), h = std::min(height, 180u);
    const std::uint32_t cx = std::uint32_t(most % width), cy = std::uint32_t(most / width);
    const std::uint32_t x = std::min(cx > w / 2 ? cx - w / 2 : 0u, width - w);
    const std::uint32_t y = std::min(cy > h / 2 ? cy - h / 2 : 0u, height - h);
    // Magnified so that a small frame's crop is at least 240 pixels wide, for its labels and to be seen.
    const std::uint32_t scale = std::clamp((240u + w - 1) / w, 1u, 4u);
    return {x, y, w, h, scale};
}

} // namespace kdop
