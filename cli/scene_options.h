// The options that pick kdop's own scenes, shared by `kdop scene` (which writes them) and
// `kdop taa` (which measures them): --scenes, --background, --camera, --reference-samples, and
// for kdop taa --upscale.
#pragma once

#include "core/input_files.h"
#include "runtime/context.h"
#include "scenes/scene_catalog.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace kdop::cli {

struct SceneChoice {
    std::vector<std::string> scenes, backgrounds;
    std::string camera = "still";
    std::uint32_t reference_samples = 0;
    double upscale = 1;

    // With `upscaling`, --upscale too.
    void add_to(CLI::App& app, bool upscaling = false) {
        app.add_option("--scenes", scenes,
                       fmt::format("Built-in scenes: {} (grass3d and asphalt3d are 3-D, rasterized on the device; "
                                   "the others 2-D) [default: grass3d asphalt3d, unless --background is given]",
                                   fmt::join(builtin_scene_names(), ", ")));
        app.add_option("--background", backgrounds,
                       "Your own background images for 2-D scenes (decoded to linear values in [0, 1], see "
                       "--input-space; tiled or cropped to --size), one scene each");
        app.add_option("--camera", camera,
                       "3-D scenes: still, or pan (the camera slides sideways, so what was behind the objects and "
                       "beyond the frame's border comes into view) [default: still]")
            ->check(CLI::IsMember({"still", "pan"}));
        app.add_option("--reference-samples", reference_samples,
                       "3-D scenes: add a reference to every frame, the mean of N samples per pixel (ghosting is "
                       "then measured against it) [default: 0, none]")
            ->check(whole_number(0, 1024));
        if (upscaling)
            app.add_option("--upscale", upscale,
                           "3-D scenes: draw the frames at --size over R (R from 1 to 4: 1.5, 1.7, 2 and 3 are FSR 2's "
                           "ratios), jittered over ceil(8 R^2) Halton phases, with references of --reference-samples "
                           "samples at --size, for a resolve to upscale to --size (docs/taa.md, \"Upscaling\") "
                           "[default: 1, no upscaling; with R > 1, 16 reference samples]")
                ->check(finite_number(1, 4));
    }

    // A usage error's message, if any: a scene or background given twice, 3-D options without a
    // 3-D scene.
    std::optional<std::string> misuse() const {
        for (std::size_t i = 0; i < scenes.size(); ++i)
            if (std::find(scenes.begin(), scenes.begin() + i, scenes[i]) != scenes.begin() + i)
                return fmt::format("--scenes: '{}' is given twice", scenes[i]);
        if (auto ok = check_distinct_files(backgrounds, "--background"); !ok) return ok.error().message;
        if (!selects_testbed_scene(scenes, backgrounds) && (camera != "still" || reference_samples > 0 || upscale > 1))
            return std::string(camera != "still"       ? "--camera"
                               : reference_samples > 0 ? "--reference-samples"
                                                       : "--upscale") +
                   ": only the 3-D scenes (grass3d, asphalt3d) take it, and none is selected";
        return std::nullopt;
    }

    bool needs_device() const { return selects_testbed_scene(scenes, backgrounds); }

    // The scenes' options at this size; `context` draws the 3-D ones.
    SceneOptions options(std::uint32_t width, std::uint32_t height, std::uint64_t seed, InputSpace space,
                         const Context* context = nullptr) const {
        // An upscaled output is measured against a reference at its size: 16 samples (NSS's) unless given.
        const std::uint32_t samples = upscale > 1 && reference_samples == 0 ? 16 : reference_samples;
        return {width, height, seed, space, context, camera == "pan", samples, upscale};
    }

    Result<std::vector<std::shared_ptr<const TaaScene>>> select(std::uint32_t width, std::uint32_t height,
                                                                std::uint64_t seed, InputSpace space,
                                                                const Context* context) const {
        return select_taa_scenes(scenes, backgrounds, options(width, height, seed, space, context));
    }
};

} // namespace kdop::cli
