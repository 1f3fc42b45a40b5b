#include "taa_scene.h"

#include "image_io.h"
#include "test_textures.h"

#include <fmt/format.h>

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

// The image repeated (or cropped) to width x height.
Image tiled(const Image& source, std::uint32_t width, std::uint32_t height) {
    Image out(width, height);
    for (std::uint32_t y = 0; y < height; ++y)
        for (std::uint32_t x = 0; x < width; ++x) out.at(x, y) = source.at(x % source.width, y % source.height);
    return out;
}

} // namespace

std::vector<TaaScene> default_taa_scenes(std::uint32_t width, std::uint32_t height, std::uint64_t seed) {
    std::vector<TaaScene> scenes{{"grass", make_texture(TextureFamily::grass, width, height, seed)},
                                 {"asphalt", make_texture(TextureFamily::asphalt, width, height, seed)}};
    for (const RealTexture& real : installed_real_textures()) {
        Image image = load_real_texture(real, width, height);
        if (image.pixels.empty()) continue;
        scenes.push_back({real.name, std::move(image)});
        break;
    }
    return scenes;
}

Result<TaaScene> read_taa_scene(const std::string& path, std::uint32_t width, std::uint32_t height, InputSpace space) {
    auto image = read_image(path, 0, space);
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
    return TaaScene{std::filesystem::path(path).stem().string(), tiled(*image, width, height)};
}

glm::vec2 r2_jitter(std::uint32_t index) {
    // R2: the plastic number g solves g^3 = g + 1; entry n is frac(0.5 + n * (1/g, 1/g^2)).
    constexpr double g = 1.32471795724474602596;
    const double n = index % 10;
    const double x = 0.5 + n / g, y = 0.5 + n / (g * g);
    return {float(x - std::floor(x) - 0.5), float(y - std::floor(y) - 0.5)};
}

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
