#include "temporal/ghosting_picture.h"

#include "flip/magma.h"
#include "temporal/trail_picture.h"

#include <fmt/format.h>

namespace kdop {

// ghosting-<scene>.png
std::string ghosting_picture_name(const std::string& scene) { return fmt::format("ghosting-{}.png", scene); }

Result<void> add_ghosting_picture(OutputSet& outputs, const TaaScene& scene, const std::string& truth_name,
                                  std::shared_ptr<const Image> truth, const std::vector<VariantKey>& keys,
                                  const std::vector<std::shared_ptr<const Image>>& trails,
                                  const std::vector<double>& ghosting, const LdrFlip& flip,
                                  const TaaSchedule& schedule) {
    const std::uint32_t width = truth->width, height = truth->height;
    std::vector<std::pair<std::string, std::shared_ptr<const Image>>> frames{{truth_name, truth}};
    std::vector<Image> maps;
    maps.reserve(trails.size()); // the picture points into it
    std::vector<LabeledFrame> labeled{
        {fmt::format("{}, frame {}", truth_name, scene.trail_frame(schedule)), truth.get()}};
    for (std::size_t v = 0; v < keys.size(); ++v) {
        auto error = flip.error_map(*truth, *trails[v]);
        if (!error) return std::unexpected(error.error());
        maps.push_back(flip::magma_image(*error, width, height));
        frames.emplace_back(keys[v].name(), trails[v]);
        labeled.push_back({keys[v].name(), trails[v].get(), &maps.back(),
                           fmt::format("ghosting {:.4f} | frame {:.4f}", ghosting[v], mean_error(*error))});
    }
    std::vector<float> ramp(256);
    for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = float(i) / float(ramp.size() - 1);
    const Image bar = flip::magma_image(ramp, std::uint32_t(ramp.size()), 1);
    const std::string caption = "LDR-FLIP against the " + (truth_name == "aliased" ? "aliased frame" : truth_name);
    const ColorScale scale{&bar, caption};
    for (const auto& [stem, image] : frames)
        for (const char* extension : {".exr", ".png"})
            outputs.add_image(fmt::format("frames/{}/{}{}", scene.name(), stem, extension), image);
    auto picture = trail_picture(labeled, scene.trail_crop(schedule), 4, &scale);
    if (!picture) return std::unexpected(picture.error());
    outputs.add_image(ghosting_picture_name(scene.name()), std::make_shared<const Image>(std::move(*picture)));
    return {};
}

} // namespace kdop
