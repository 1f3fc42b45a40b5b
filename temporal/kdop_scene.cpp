#include "kdop_scene.h"

#include "scene3d.h"
#include "taa_scene.h"
#include "testbed_scene.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace kdop {
namespace {

const char* const kTestbedScenes[] = {"grass3d", "asphalt3d"};

// The testbed's scenes, by name.
std::optional<Scene3d> testbed_scene(const std::string& name, std::uint64_t seed) {
    if (name == "grass3d") return grass3d_scene(seed);
    if (name == "asphalt3d") return asphalt3d_scene(seed);
    return std::nullopt;
}

bool is_testbed_scene(const std::string& name) {
    return std::find(std::begin(kTestbedScenes), std::end(kTestbedScenes), name) != std::end(kTestbedScenes);
}

} // namespace

std::shared_ptr<const FrameSource> shimmer_frames(const TaaScene& scene, const TaaSchedule& schedule) {
    return scene.frames(scene.name() + "-shimmer", schedule.warmup + schedule.frames, false, true);
}

std::shared_ptr<const FrameSource> ghosting_frames(const TaaScene& scene, const TaaSchedule& schedule) {
    return scene.frames(scene.name() + "-ghosting", schedule.warmup + schedule.frames, true, false);
}

std::vector<std::string> builtin_scene_names() {
    std::vector<std::string> names(std::begin(kTestbedScenes), std::end(kTestbedScenes));
    for (const std::string& name : sprite_scene_names()) names.push_back(name);
    return names;
}

bool selects_testbed_scene(const std::vector<std::string>& names, const std::vector<std::string>& backgrounds) {
    if (names.empty() && backgrounds.empty()) return true;
    return std::any_of(names.begin(), names.end(), is_testbed_scene);
}

Result<std::vector<std::shared_ptr<const TaaScene>>> select_taa_scenes(const std::vector<std::string>& names,
                                                                       const std::vector<std::string>& backgrounds,
                                                                       const SceneOptions& o) {
    std::vector<std::string> wanted = names;
    if (names.empty() && backgrounds.empty()) wanted.assign(std::begin(kTestbedScenes), std::end(kTestbedScenes));
    std::vector<std::shared_ptr<const TaaScene>> out;
    std::vector<SpriteScene> sprites;
    for (const std::string& name : wanted) {
        if (auto scene = testbed_scene(name, o.seed)) {
            if (!o.context)
                return fail(fmt::format("--scenes: {} is drawn on a Vulkan device, and none is open", name));
            auto created = TestbedScene::create(*o.context, std::move(*scene), o.width, o.height, o.camera_pan,
                                                o.reference_samples);
            if (!created) return fail(fmt::format("--scenes: {}: {}", name, created.error().message));
            out.push_back(std::move(*created));
            continue;
        }
        if (sprites.empty()) sprites = default_sprite_scenes(o.width, o.height, o.seed);
        auto it = std::find_if(sprites.begin(), sprites.end(), [&](const SpriteScene& s) { return s.name() == name; });
        if (it == sprites.end())
            return fail(fmt::format("--scenes: no scene '{}'; the built-in scenes here: {}", name,
                                    fmt::join(builtin_scene_names(), ", ")));
        out.push_back(std::make_shared<SpriteScene>(*it));
    }
    for (const std::string& path : backgrounds) {
        auto scene = read_sprite_scene(path, o.width, o.height, o.input_space);
        if (!scene) return std::unexpected(scene.error());
        if (std::any_of(out.begin(), out.end(), [&](const auto& s) { return s->name() == scene->name(); }))
            return fail(fmt::format("--background: {}: a scene is already called '{}'", path, scene->name()));
        out.push_back(std::make_shared<SpriteScene>(std::move(*scene)));
    }
    return out;
}

} // namespace kdop
