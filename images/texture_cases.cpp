#include "images/texture_cases.h"

#include "images/random.h"

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/vec3.hpp>

#include <cmath>

namespace kdop {
namespace {

constexpr TextureFamily kFamilies[] = {TextureFamily::grass,     TextureFamily::edges, TextureFamily::asphalt,
                                       TextureFamily::gradient,  TextureFamily::flat,  TextureFamily::hdr,
                                       TextureFamily::highlights};
constexpr HistoryModel kModels[] = {HistoryModel::same, HistoryModel::shifted, HistoryModel::moved_object,
                                    HistoryModel::other_texture};

// Smooth value noise in [0, 1): hashed lattice values, interpolated with a smoothstep.
double value_noise(double x, double y, std::uint64_t seed) {
    double fx = std::floor(x), fy = std::floor(y);
    auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy);
    double tx = x - fx, ty = y - fy;
    tx = tx * tx * (3 - 2 * tx);
    ty = ty * ty * (3 - 2 * ty);
    double a = hash_to_unit(ix, iy, seed), b = hash_to_unit(ix + 1, iy, seed);
    double c = hash_to_unit(ix, iy + 1, seed), d = hash_to_unit(ix + 1, iy + 1, seed);
    return glm::mix(glm::mix(a, b, tx), glm::mix(c, d, tx), ty);
}

template <class Shader>
Image shade(std::uint32_t w, std::uint32_t h, Shader shader) {
    Image image(w, h);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) image.at(x, y) = glm::vec4(glm::vec3(shader(double(x), double(y))), 1.0f);
    return image;
}

Image grass(std::uint32_t w, std::uint32_t h, std::uint64_t seed) {
    Random grain(seed);
    const glm::dvec3 yellow(0.40, 0.50, 0.06), deep(0.05, 0.30, 0.08), blue(0.04, 0.22, 0.16);
    return shade(w, h, [&](double x, double y) {
        double blade = value_noise(x * 0.7, y * 0.12, seed + 1); // blades: narrow across, long down
        double gaps = value_noise(x * 0.45, y * 0.3, seed + 2);
        double hue = 0.7 * value_noise(x * 0.2, y * 0.05, seed + 3) + 0.3 * grain.uniform();
        double luma = (0.25 + 0.9 * blade) * (0.7 + 0.6 * grain.uniform());
        if (gaps < 0.18) luma *= 0.15; // shadow between blades
        glm::dvec3 color = hue < 0.5 ? glm::mix(yellow, deep, hue * 2) : glm::mix(deep, blue, hue * 2 - 1);
        return color * luma;
    });
}

Image asphalt(std::uint32_t w, std::uint32_t h, std::uint64_t seed) {
    Random grain(seed);
    return shade(w, h, [&](double x, double y) {
        double base = 0.10 + 0.06 * value_noise(x * 0.05, y * 0.05, seed + 1);
        double value = base + (grain.uniform() - 0.5) * 0.10;
        double speck = grain.uniform();
        if (speck < 0.03) value = 0.35 + 0.25 * grain.uniform(); // aggregate stone
        if (speck > 0.97) value = 0.015;                         // pit
        return glm::dvec3(1.0, 0.98, 0.95) * value;
    });
}

Image edges(std::uint32_t w, std::uint32_t h, std::uint64_t seed) {
    const glm::dvec3 palette[] = {{0.85, 0.10, 0.08}, {0.10, 0.55, 0.90}, {0.95, 0.85, 0.20}, {0.05, 0.05, 0.06},
                                  {0.90, 0.90, 0.88}, {0.20, 0.70, 0.25}, {0.60, 0.15, 0.70}, {0.95, 0.45, 0.10}};
    Random random(seed);
    struct Disk {
        double x, y, r;
        int color;
    };
    std::vector<Disk> disks;
    for (int i = 0; i < 8; ++i)
        disks.push_back({random.uniform(0, w), random.uniform(0, h), random.uniform(4, 14), int(random.next() % 8)});
    return shade(w, h, [&](double x, double y) {
        for (const Disk& d : disks)
            if ((x - d.x) * (x - d.x) + (y - d.y) * (y - d.y) < d.r * d.r) return palette[d.color];
        auto cell = static_cast<int>(hash_to_unit(std::int64_t(x) / 12, std::int64_t(y) / 12, seed) * 8);
        return palette[cell];
    });
}

Image gradient(std::uint32_t w, std::uint32_t h, std::uint64_t) {
    const glm::dvec3 c00(0.90, 0.20, 0.10), c10(0.10, 0.60, 0.90), c01(0.20, 0.90, 0.30), c11(0.95, 0.90, 0.70);
    return shade(w, h, [&](double x, double y) {
        double u = x / std::max(1u, w - 1), v = y / std::max(1u, h - 1);
        glm::dvec3 color = glm::mix(glm::mix(c00, c10, u), glm::mix(c01, c11, u), v);
        return color + 0.05 * std::sin(6.283185307179586 * (u + v));
    });
}

Image flat(std::uint32_t w, std::uint32_t h, std::uint64_t) {
    const glm::dvec3 quadrant[] = {{0.37, 0.37, 0.37}, {0.80, 0.25, 0.10}, {0.0, 0.0, 0.0}, {40.0, 38.0, 30.0}};
    return shade(w, h, [&](double x, double y) { return quadrant[(x < w / 2 ? 0 : 1) + (y < h / 2 ? 0 : 2)]; });
}

Image hdr(std::uint32_t w, std::uint32_t h, std::uint64_t seed) {
    Random random(seed);
    Image image = shade(w, h, [&](double x, double y) {
        double v = 0.03 + 0.05 * value_noise(x * 0.1, y * 0.1, seed + 1) + 0.01 * random.uniform();
        return glm::dvec3(v, v * 0.9, v * 0.8);
    });
    // Highlights: about 1 pixel in 100 is the center of a small specular spot.
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) {
            if (random.uniform() >= 0.01) continue;
            double peak = std::exp(random.uniform(std::log(5.0), std::log(60000.0)));
            glm::vec3 tint(1.0f, float(random.uniform(0.7, 1.0)), float(random.uniform(0.5, 1.0)));
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    int px = int(x) + dx, py = int(y) + dy;
                    if (px < 0 || py < 0 || px >= int(w) || py >= int(h)) continue;
                    float falloff = (dx == 0 && dy == 0) ? 1.0f : (dx == 0 || dy == 0) ? 0.3f : 0.1f;
                    glm::vec4& p = image.at(px, py);
                    p = glm::max(p, glm::vec4(tint * float(peak) * falloff, 1.0f));
                }
        }
    return image;
}

// Grass with 3% of its pixels raised to highlights whose brightest channel is 1e2 to 5e4
// (log-uniform) and whose other channels are 1e-3 to 1 of it: lone bright pixels of any hue, next to
// dim neighbors, as specular glints and emissive sparks are in HDR frames. Where one channel of a
// pixel is far brighter than the others, float32 rounding and any padding that follows the pixel's
// brightest channel meet the dim channels' slabs.
Image highlights(std::uint32_t w, std::uint32_t h, std::uint64_t seed) {
    Image image = grass(w, h, seed);
    Random random(seed + 7);
    for (glm::vec4& p : image.pixels) {
        if (random.uniform() >= 0.03) continue;
        const double peak = std::exp(random.uniform(std::log(1e2), std::log(5e4)));
        const int brightest = int(random.next() % 3);
        for (int c = 0; c < 3; ++c)
            p[c] = float(c == brightest ? peak : peak * std::exp(random.uniform(std::log(1e-3), 0.0)));
    }
    return image;
}

} // namespace

std::span<const TextureFamily> texture_families() { return kFamilies; }
std::span<const HistoryModel> history_models() { return kModels; }

const char* to_string(TextureFamily family) {
    switch (family) {
    case TextureFamily::grass: return "grass";
    case TextureFamily::asphalt: return "asphalt";
    case TextureFamily::edges: return "edges";
    case TextureFamily::gradient: return "gradient";
    case TextureFamily::flat: return "flat";
    case TextureFamily::hdr: return "hdr";
    case TextureFamily::highlights: return "highlights";
    }
    return "?";
}

const char* to_string(HistoryModel model) {
    switch (model) {
    case HistoryModel::same: return "same";
    case HistoryModel::shifted: return "shifted";
    case HistoryModel::moved_object: return "moved-object";
    case HistoryModel::other_texture: return "other-texture";
    }
    return "?";
}

Image make_texture(TextureFamily family, std::uint32_t w, std::uint32_t h, std::uint64_t seed) {
    switch (family) {
    case TextureFamily::grass: return grass(w, h, seed);
    case TextureFamily::asphalt: return asphalt(w, h, seed);
    case TextureFamily::edges: return edges(w, h, seed);
    case TextureFamily::gradient: return gradient(w, h, seed);
    case TextureFamily::flat: return flat(w, h, seed);
    case TextureFamily::hdr: return hdr(w, h, seed);
    case TextureFamily::highlights: return highlights(w, h, seed);
    }
    return {};
}

Image make_history(const Image& current, HistoryModel model, const Image& other) {
    Image history = current;
    const int w = static_cast<int>(current.width), h = static_cast<int>(current.height);
    switch (model) {
    case HistoryModel::same: break;
    case HistoryModel::shifted:
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) history.at(x, y) = current.clamped(x - 3, y - 2);
        break;
    case HistoryModel::moved_object: {
        const double cx = w * 0.35, cy = h * 0.5, r = h * 0.22;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                history.at(x, y) = current.clamped(x - 1, y);
                double dx = x - cx, dy = y - cy;
                if (dx * dx + dy * dy < r * r)
                    history.at(x, y) =
                        dy > r * 0.55 ? glm::vec4(0.02f, 0.02f, 0.02f, 1) : glm::vec4(0.60f, 0.03f, 0.02f, 1);
            }
        break;
    }
    case HistoryModel::other_texture: history = other; break;
    }
    return history;
}

} // namespace kdop
