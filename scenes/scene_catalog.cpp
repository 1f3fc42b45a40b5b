#include "scenes/scene_catalog.h"

#include "scenes/sprite_scene.h"
#include "scenes/testbed_scene.h"
#include "testbed/scene3d.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace kdop {
namespace {

// The testbed's scenes: the one place their names are listed.
struct TestbedEntry {
    const char* name;
    Scene3d (*make)(std::uint64_t seed);
};
constexpr TestbedEntry kTestbedScenes[] = {{"grass3d", grass3d_scene}, {"asphalt3d", asphalt3d_scene}};

const TestbedEntry* testbed_entry(const std::string& name) {
    for (const TestbedEntry& e : kTestbedScenes)
        if (name == e.name) return &e;
    return nullptr;
}

bool is_testbed_scene(const std::string& name) { return testbed_entry(name) != nullptr; }

std::vector<std::string> testbed_names() {
    std::vector<std::string> names;
    for (const TestbedEntry& e : kTestbedScenes) names.push_back(e.name);
    return names;
}

} // namespace

std::vector<std::string> builtin_scene_names() {
    std::vector<std::string> names = testbed_names();
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
    if (names.empty() && backgrounds.empty())
        for (const TestbedEntry& e : kTestbedScenes) wanted.push_back(e.name);
    std::vector<std::shared_ptr<const TaaScene>> out;
    std::vector<SpriteScene> sprites;
    for (const std::string& name : wanted) {
        if (const TestbedEntry* testbed = testbed_entry(name)) {
            if (!o.context)
                return fail(fmt::format("--scenes: {} is drawn on a Vulkan device, and none is open", name));
            auto created = TestbedScene::create(*o.context, testbed->make(o.seed), o.width, o.height, o.camera_pan,
                                                o.reference_samples, o.upscale);
            if (!created) return fail(fmt::format("--scenes: {}: {}", name, created.error().message));
            out.push_back(std::move(*created));
            continue;
        }
        if (o.upscale > 1)
            return usage_fail(
                fmt::format("--scenes: {} is a 2-D scene, drawn at one size; --upscale takes the 3-D ones ({})", name,
                            fmt::join(testbed_names(), ", ")));
        if (sprites.empty()) sprites = default_sprite_scenes(o.width, o.height, o.seed);
        auto it = std::find_if(sprites.begin(), sprites.end(), [&](const SpriteScene& s) { return s.name() == name; });
        if (it == sprites.end())
            return fail(fmt::format("--scenes: no scene '{}'; the built-in scenes here: {}", name,
                                    fmt::join(builtin_scene_names(), ", ")));
        out.push_back(std::make_shared<SpriteScene>(*it));
    }
    if (o.upscale > 1 && !backgrounds.empty())
        return usage_fail("--background: a 2-D scene is drawn at one size; --upscale takes the 3-D scenes");
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
