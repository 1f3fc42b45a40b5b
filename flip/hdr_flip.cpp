#include "hdr_flip.h"

#include <fmt/format.h>

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>

namespace kdop {
namespace {

constexpr const char* kChannelNames[] = {"R", "G", "B"};

using Curve = ToneCurve;
constexpr Curve kReinhard{0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 1.0f};
constexpr Curve kAces{0.6f * 0.6f * 2.51f, 0.6f * 0.03f, 0.0f, 0.6f * 0.6f * 2.43f, 0.6f * 0.59f, 0.14f};
constexpr Curve kHable{0.231683f, 0.013791f, 0.0f, 0.18f, 0.3f, 0.018f};

const Curve& curve(ToneMapper t) { return t == ToneMapper::aces ? kAces : t == ToneMapper::hable ? kHable : kReinhard; }

float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// The larger root of T(x) = 0.85, T the tone mapper's curve (computeExposures, solveSecondDegree):
// the input that the curve maps to 0.85 of white.
float x_max(ToneMapper t) {
    const Curve& k = curve(t);
    const float target = 0.85f;
    const float a = k.a - target * k.d, b = k.b - target * k.e, c = k.c - target * k.f;
    if (a == 0.0f) return -c / b;
    const float d1 = -0.5f * (b / a);
    const float d2 = std::sqrt(d1 * d1 - c / a);
    return d1 + d2;
}

} // namespace

std::optional<ToneMapper> parse_tone_mapper(std::string_view name) {
    if (name == "aces") return ToneMapper::aces;
    if (name == "hable") return ToneMapper::hable;
    if (name == "reinhard") return ToneMapper::reinhard;
    return std::nullopt;
}

const char* to_string(ToneMapper t) {
    switch (t) {
    case ToneMapper::aces: return "aces";
    case ToneMapper::hable: return "hable";
    case ToneMapper::reinhard: return "reinhard";
    }
    return "?";
}

const ToneCurve& tone_curve(ToneMapper t) { return curve(t); }

glm::vec3 tone_map(ToneMapper t, glm::vec3 color) {
    if (t == ToneMapper::reinhard) return color * (1.0f / (1.0f + luminance(color)));
    const Curve& k = curve(t);
    return ((color * color) * k.a + color * k.b + k.c) / (color * color * k.d + color * k.e + k.f);
}

float ExposureRange::exposure(int i) const {
    return count == 1 ? start : start + float(i) * ((stop - start) / float(count - 1));
}

Result<ExposureRange> exposure_range(const Image& reference, const ExposureOptions& options) {
    ExposureRange range;
    if (!options.start || !options.stop) {
        std::vector<float> luminances(reference.pixels.size());
        for (std::size_t i = 0; i < luminances.size(); ++i) luminances[i] = luminance(glm::vec3(reference.pixels[i]));
        if (luminances.empty()) return fail("the reference image is empty");
        const float largest = *std::max_element(luminances.begin(), luminances.end());
        const std::size_t middle = luminances.size() / 2;
        std::nth_element(luminances.begin(), luminances.begin() + std::ptrdiff_t(middle), luminances.end());
        const float median = luminances[middle];
        const float x = x_max(options.tone_mapper);
        if (!options.start && !(largest > 0.0f))
            return fail("the reference's largest luminance is 0, which puts the start exposure at infinity; give "
                        "--start-exposure");
        if (!options.stop && !(median > 0.0f))
            return fail("the reference's median luminance is 0 (at least half its pixels are black), which puts the "
                        "stop exposure at infinity; give --stop-exposure");
        range.start = options.start ? *options.start : std::log2(x / largest);
        range.stop = options.stop ? *options.stop : std::log2(x / median);
    } else {
        range.start = *options.start;
        range.stop = *options.stop;
    }
    if (!std::isfinite(range.start) || !std::isfinite(range.stop))
        return fail(fmt::format("the exposure range {} to {} is not finite", range.start, range.stop));
    if (range.start > range.stop)
        return fail(fmt::format("the start exposure {} is above the stop exposure {}{}", range.start, range.stop,
                                options.start && options.stop ? "" : " (one of them derived from the reference)"));
    if (options.count && *options.count < 1)
        return fail(fmt::format("{} exposures: HDR-FLIP needs at least 1", *options.count));
    range.count = options.count ? *options.count : int(std::max(2.0f, std::ceil(range.stop - range.start)));
    return range;
}

Result<void> check_hdr_image(const Image& image, const std::string& what) {
    if (image.width == 0 || image.height == 0) return fail(fmt::format("{}: the image is empty", what));
    for (std::uint32_t y = 0; y < image.height; ++y)
        for (std::uint32_t x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float v = image.at(x, y)[c];
                if (!(v >= 0.0f) || std::isinf(v)) // NaN fails too
                    return fail(fmt::format("{}: pixel ({}, {}) has {} = {}; HDR-FLIP takes finite linear RGB that "
                                            "is not negative",
                                            what, x, y, kChannelNames[c], v));
            }
    return {};
}

Image HdrFlip::tone_mapped(const Image& image, ToneMapper tone_mapper, float exposure) {
    const float scale = std::pow(2.0f, exposure);
    Image out(image.width, image.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const glm::vec3 mapped = tone_map(tone_mapper, glm::vec3(image.pixels[i]) * scale);
        out.pixels[i] = glm::vec4(glm::clamp(mapped, 0.0f, 1.0f), 1.0f);
    }
    return out;
}

Result<HdrFlipMaps> HdrFlip::maps(const Image& reference, const Image& test, const ExposureOptions& options) const {
    if (auto ok = check_hdr_image(reference, "reference image"); !ok) return std::unexpected(ok.error());
    if (test.width != reference.width || test.height != reference.height)
        return fail(fmt::format("test image: {}x{}, but the reference image is {}x{}", test.width, test.height,
                                reference.width, reference.height));
    if (auto ok = check_hdr_image(test, "test image"); !ok) return std::unexpected(ok.error());
    auto range = exposure_range(reference, options);
    if (!range) return std::unexpected(range.error());

    HdrFlipMaps out;
    out.range = *range;
    out.error.assign(reference.pixels.size(), 0.0f);
    out.exposure.assign(reference.pixels.size(), 0.0f);
    for (int i = 0; i < range->count; ++i) {
        const float exposure = range->exposure(i);
        auto map = ldr_.error_map(tone_mapped(reference, options.tone_mapper, exposure),
                                  tone_mapped(test, options.tone_mapper, exposure));
        if (!map) return std::unexpected(map.error());
        const float where = range->count == 1 ? 0.0f : float(i) / float(range->count - 1);
        for (std::size_t p = 0; p < map->size(); ++p)
            if ((*map)[p] > out.error[p]) {
                out.error[p] = (*map)[p];
                out.exposure[p] = where;
            }
    }
    out.mean = mean_error(out.error);
    return out;
}

} // namespace kdop
