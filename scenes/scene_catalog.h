// The scenes kdop draws, by name: the one place that knows every content source kdop ships (the
// 3-D testbed's and the 2-D sprite scenes) and the options they are made with.
#pragma once

#include "core/result.h"
#include "images/image_io.h"
#include "runtime/context.h"
#include "scenes/taa_scene.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace kdop {

struct SceneOptions {
    std::uint32_t width = 320, height = 180;
    std::uint64_t seed = 1;                         // of the synthetic textures and the testbed's scenes
    InputSpace input_space = InputSpace::from_file; // of --background images
    const Context* context = nullptr;               // where the 3-D scenes are drawn; must outlive them
    bool camera_pan = false;                        // 3-D scenes: the camera slides sideways (--camera pan)
    std::uint32_t reference_samples = 0;            // 3-D scenes: > 0 adds a supersampled reference per frame
    double upscale = 1; // 3-D scenes: > 1 draws the frames smaller by this ratio, to be upscaled to width x height
};

// The built-in scenes: the 3-D testbed's two, then the 2-D ones.
std::vector<std::string> builtin_scene_names();

// Whether select_taa_scenes(names, backgrounds, ...) picks a 3-D scene, and so needs a context.
bool selects_testbed_scene(const std::vector<std::string>& names, const std::vector<std::string>& backgrounds);

// The scenes `names` asks for (built-in, by name), then one per image in `backgrounds` (2-D), in
// that order; both empty: grass3d and asphalt3d. Errors name the option (--scenes, --background).
Result<std::vector<std::shared_ptr<const TaaScene>>> select_taa_scenes(const std::vector<std::string>& names,
                                                                       const std::vector<std::string>& backgrounds,
                                                                       const SceneOptions& options);

} // namespace kdop
