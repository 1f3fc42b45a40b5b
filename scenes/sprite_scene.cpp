#include "scenes/sprite_scene.h"

#include "core/file_name.h"
#include "core/shown_text.h"
#include "images/image_io.h"
#include "images/texture_cases.h"

#include <fmt/format.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kdop {
namespace {

// Periods of the two sine paths, in frames: unequal, so the objects cross at changing places.
constexpr double kCarPeriod = 160, kShadowPeriod = 110;

glm::vec2 car_center(double t, glm::vec2 frame) {
    const double phase = 2 * std::numbers::pi * t / kCarPeriod;
    return {frame.x * (0.5 + 0.3 * std::sin(phase)), frame.y * 0.55};
}

glm::vec2 shadow_center(double t, glm::vec2 frame) {
    const double phase = 2 * std::numbers::pi * t / kShadowPeriod + 1.0;
    return {frame.x * (0.5 - 0.32 * std::sin(phase)), frame.y * (0.3 + 0.12 * std::cos(phase))};
}

constexpr float kTexelsPerPixel = 1.25f;
const glm::vec3 kCarColor(0.62f, 0.018f, 0.012f); // linear; a saturated red
const glm::vec3 kShadowColor(0.012f, 0.011f, 0.010f);
constexpr float kCarDepth = 0.5f, kGroundDepth = 1.0f;

glm::vec3 texel(const Image& background, glm::ivec2 t) {
    const int w = int(background.width), h = int(background.height);
    return glm::vec3(background.at(std::uint32_t(((t.x % w) + w) % w), std::uint32_t(((t.y % h) + h) % h)));
}

// The background at pixel coordinates x: repeated, minified, bilinear.
glm::vec3 background_at(const Image& background, glm::vec2 x) {
    const glm::vec2 t = x * kTexelsPerPixel - 0.5f, f = t - glm::floor(t);
    const glm::ivec2 i(glm::floor(t));
    return glm::mix(glm::mix(texel(background, i), texel(background, i + glm::ivec2(1, 0)), f.x),
                    glm::mix(texel(background, i + glm::ivec2(0, 1)), texel(background, i + glm::ivec2(1, 1)), f.x),
                    f.y);
}

bool inside_car(glm::vec2 x, const FrameState& s, glm::vec2 frame) {
    const float angle = 0.2f;
    const glm::vec2 d = x - s.car_center;
    const glm::vec2 local(std::cos(angle) * d.x + std::sin(angle) * d.y,
                          -std::sin(angle) * d.x + std::cos(angle) * d.y);
    return std::abs(local.x) < 0.14f * frame.x && std::abs(local.y) < 0.07f * frame.x;
}

bool inside_shadow(glm::vec2 x, const FrameState& s, glm::vec2 frame) {
    const glm::vec2 d = (x - s.shadow_center) / (glm::vec2(0.09f, 0.05f) * frame.x);
    return glm::dot(d, d) < 1.0f;
}

// The image repeated (or cropped) to width x height.
Image tiled(const Image& source, std::uint32_t width, std::uint32_t height) {
    Image out(width, height);
    for (std::uint32_t y = 0; y < height; ++y)
        for (std::uint32_t x = 0; x < width; ++x) out.at(x, y) = source.at(x % source.width, y % source.height);
    return out;
}

} // namespace

std::vector<SpriteScene> default_sprite_scenes(std::uint32_t width, std::uint32_t height, std::uint64_t seed) {
    std::vector<SpriteScene> scenes{{"grass", make_texture(TextureFamily::grass, width, height, seed)},
                                    {"asphalt", make_texture(TextureFamily::asphalt, width, height, seed)}};
    for (const RealTexture& real : installed_real_textures()) {
        Image image = load_real_texture(real, width, height);
        if (image.pixels.empty()) continue;
        scenes.emplace_back(real.name, std::move(image));
        break;
    }
    return scenes;
}

std::vector<std::string> sprite_scene_names() {
    std::vector<std::string> names{"grass", "asphalt"};
    const std::vector<RealTexture> real = installed_real_textures();
    if (!real.empty()) names.push_back(real.front().name);
    return names;
}

Result<SpriteScene> read_sprite_scene(const std::string& path, std::uint32_t width, std::uint32_t height,
                                      InputSpace space) {
    // The scene, its rows, charts and frames are named after the image's stem (core/file_name.h).
    const std::string name = std::filesystem::path(path).stem().string();
    if (auto problem = name_problem(name))
        return usage_fail(fmt::format("--background: {}: the scene would be named after the file, and the name {}; "
                                      "rename the file",
                                      shown_text(path, 300), *problem));
    // Only the corner the frame is tiled or cropped from is read: a 10000x10000 PNG under a 320x180
    // frame costs 320x180 pixels and a strip of rows, not 2 GB.
    auto image = read_image_corner(path, width, height, space);
    if (!image) return fail(fmt::format("--background: {}", image.error().message));
    for (std::uint32_t y = 0; y < image->height; ++y)
        for (std::uint32_t x = 0; x < image->width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float v = image->at(x, y)[c];
                if (!(v >= 0.0f && v <= 1.0f))
                    return fail(fmt::format("--background: {}: pixel ({}, {}) has {} {}, outside [0, 1]; the "
                                            "ghosting and shimmer metric is LDR-FLIP, which takes linear values "
                                            "from 0 to 1",
                                            path, x, y, "RGB"[c], v));
            }
    return SpriteScene(name, tiled(*image, width, height));
}

LoadedFrame render_scene(const Image& background, const FrameState& s) {
    const std::uint32_t width = background.width, height = background.height;
    const glm::vec2 frame{float(width), float(height)};
    LoadedFrame out;
    out.color = Image(width, height);
    out.depth = Image(width, height, glm::vec4(kGroundDepth, 0, 0, 1));
    out.motion.assign(std::size_t(width) * height, glm::vec2(0));
    for (std::uint32_t y = 0; y < height; ++y)
        for (std::uint32_t x = 0; x < width; ++x) {
            const glm::vec2 at = glm::vec2(float(x), float(y)) + 0.5f + s.jitter;
            const std::size_t i = std::size_t(y) * width + x;
            glm::vec3 color = background_at(background, at);
            // A surface that moved by m since last frame was at x - m.
            if (inside_car(at, s, frame)) {
                color = kCarColor;
                out.motion[i] = -s.car_motion;
                out.depth->pixels[i].r = kCarDepth;
            } else if (inside_shadow(at, s, frame)) {
                color = kShadowColor;
                out.motion[i] = -s.shadow_motion;
            }
            out.color.pixels[i] = glm::vec4(color, 1);
        }
    return out;
}

FrameState SceneFrames::state(std::size_t index) const {
    return frame_state(std::uint32_t(index), background_.width, background_.height, animate_, jitter_);
}

std::optional<glm::vec2> SceneFrames::jitter(std::size_t index) const {
    if (!jitter_) return std::nullopt;
    return state(index).jitter;
}

std::string SpriteScene::content() const {
    return fmt::format("2-D: the {}x{} background, repeated and minified by {} texels per pixel, under a red box and "
                       "a dark ellipse",
                       background_.width, background_.height, kTexelsPerPixel);
}

std::shared_ptr<const FrameSource> SpriteScene::frames(const std::string& name, std::size_t count, bool animate,
                                                       bool jitter) const {
    return std::make_shared<SceneFrames>(name, background_, count, animate, jitter);
}

std::uint32_t SpriteScene::trail_frame(const TaaSchedule& schedule) const {
    std::uint32_t best = schedule.warmup;
    float fastest = -1;
    for (std::uint32_t f = schedule.warmup; f < schedule.warmup + schedule.frames; ++f) {
        const float speed = std::abs(frame_state(f, width(), height(), true, false).car_motion.x);
        if (speed > fastest) fastest = speed, best = f;
    }
    return best;
}

TrailCrop SpriteScene::trail_crop(const TaaSchedule& schedule) const {
    const std::uint32_t width = this->width(), height = this->height();
    const FrameState s = frame_state(trail_frame(schedule), width, height, true, false);
    TrailCrop crop{0, 0, std::max(width / 2, 1u), std::max(height / 2, 1u), 2};
    const float behind = s.car_motion.x > 0 ? -0.15f * float(width) : 0.15f * float(width);
    auto corner = [](float center, std::uint32_t side, std::uint32_t frame) {
        return std::uint32_t(std::clamp(center - float(side) / 2, 0.0f, float(frame - side)));
    };
    crop.x = corner(s.car_center.x + behind, crop.width, width);
    crop.y = corner(s.car_center.y, crop.height, height);
    return crop;
}

std::string SceneFrames::frame_label(std::size_t index) const { return fmt::format("{}, frame {}", name_, index); }

FrameState frame_state(std::uint32_t frame, std::uint32_t width, std::uint32_t height, bool animate, bool jitter) {
    const glm::vec2 size(width, height);
    const double t = animate ? frame : 0.0;
    FrameState s;
    if (jitter) s.jitter = r2_jitter(frame);
    s.car_center = car_center(t, size);
    s.shadow_center = shadow_center(t, size);
    if (animate) {
        s.car_motion = s.car_center - car_center(t - 1, size);
        s.shadow_motion = s.shadow_center - shadow_center(t - 1, size);
    }
    return s;
}

} // namespace kdop
