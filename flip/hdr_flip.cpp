#include "flip/hdr_flip.h"

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

glm::vec3 tone_map(ToneMapper t, glm::vec3 color, float scale) {
    // Beyond kLimit the curves are at their limits to float's precision, and x * x (1e36) is still
    // finite below it: the limit forms below keep 1e19, and an exposed value that overflowed to
    // infinity, from becoming inf / inf. shader_templates/flip.comp.in computes the same.
    constexpr float kLimit = 1e18f;
    const glm::vec3 x = color * scale;
    if (t == ToneMapper::reinhard) {
        const float l = luminance(x);
        // x / (1 + L(x)) tends to color / L(color), whatever the scale.
        if (l > kLimit) return color * (1.0f / luminance(color));
        return x * (1.0f / (1.0f + l));
    }
    const Curve& k = curve(t);
    glm::vec3 out;
    for (int c = 0; c < 3; ++c) {
        const float v = x[c];
        if (v > kLimit) {
            // (a x^2 + b x + c) / (d x^2 + e x + f) with x^2 divided out: a / d at infinity.
            const float y = 1.0f / v;
            out[c] = (k.a + (k.b + k.c * y) * y) / (k.d + (k.e + k.f * y) * y);
        } else {
            out[c] = ((v * v) * k.a + v * k.b + k.c) / (v * v * k.d + v * k.e + k.f);
        }
    }
    return out;
}

float ExposureRange::exposure(int i) const {
    return count == 1 ? start : start + float(i) * ((stop - start) / float(count - 1));
}

namespace {

// Exposures whose 2^exposure is a normal float.
constexpr float kMostStops = 126.0f;

} // namespace

Luminances luminances_of(const Image& image) {
    std::vector<float> values(image.pixels.size());
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = luminance(glm::vec3(image.pixels[i]));
    Luminances out;
    if (values.empty()) return out;
    out.largest = *std::max_element(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(middle), values.end());
    out.median = values[middle];
    if (!(out.median > 0.0f) && out.largest > 0.0f) {
        std::erase_if(values, [](float v) { return !(v > 0.0f); });
        const std::size_t lit_middle = values.size() / 2;
        std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(lit_middle), values.end());
        out.median = values[lit_middle];
        out.median_of_lit = true;
    }
    return out;
}

Result<ExposureRange> exposure_range(const Image& reference, const ExposureOptions& options, const Image* test) {
    if ((!options.start || !options.stop) && reference.pixels.empty()) return fail("the reference image is empty");
    const LuminancesSource of_test = [test]() -> Result<Luminances> { return luminances_of(*test); };
    return exposure_range(
        options, [&]() -> Result<Luminances> { return luminances_of(reference); }, test ? of_test : nullptr);
}

Result<ExposureRange> exposure_range(const ExposureOptions& options, const LuminancesSource& reference,
                                     const LuminancesSource& test) {
    ExposureRange range;
    if (!options.start || !options.stop) {
        auto found = reference();
        if (!found) return std::unexpected(found.error());
        Luminances l = *found;
        const char* from = "the reference's";
        if (!(l.largest > 0.0f) && test) {
            found = test();
            if (!found) return std::unexpected(found.error());
            l = *found;
            from = "the test image's";
            if (!(l.largest > 0.0f)) {
                // Both black: every exposure gives them the same tone-mapped black, so no error.
                range.count = 1;
                range.note = "both images are black, so HDR-FLIP is 0 at any exposure: measured at exposure 0";
                return range;
            }
            range.note = "the reference is black: the exposure range is the test image's";
        }
        const float x = x_max(options.tone_mapper);
        if (!options.start && !(l.largest > 0.0f))
            return fail("the reference's largest luminance is 0, which puts the start exposure at infinity; give "
                        "--start-exposure");
        if (l.median_of_lit && !options.stop)
            range.note += fmt::format("{}at least half of {} pixels are black: the stop exposure is from the median "
                                      "of the others",
                                      range.note.empty() ? "" : "; ", from);
        // In double: x / 1e-40 is beyond float before its log2 is taken.
        range.start = options.start ? *options.start : float(std::log2(double(x) / l.largest));
        range.stop = options.stop ? *options.stop : float(std::log2(double(x) / l.median));
        const struct {
            float exposure;
            bool given;
            const char* which;
            float luminance;
        } ends[] = {{range.start, bool(options.start), "largest", l.largest},
                    {range.stop, bool(options.stop), "median", l.median}};
        for (const auto& end : ends)
            if (!end.given && !(std::abs(end.exposure) <= kMostStops))
                return fail(fmt::format("{} {} luminance {:.3g} puts an exposure at {:.1f} stops, beyond the {:g} that "
                                        "float can scale by; give --start-exposure and --stop-exposure",
                                        from, end.which, end.luminance, end.exposure, kMostStops));
    } else {
        range.start = *options.start;
        range.stop = *options.stop;
    }
    if (!(std::abs(range.start) <= kMostStops) || !(std::abs(range.stop) <= kMostStops))
        return fail(fmt::format("the exposure range {} to {} reaches beyond the {:g} stops float can scale by",
                                range.start, range.stop, kMostStops));
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
        const glm::vec3 mapped = tone_map(tone_mapper, glm::vec3(image.pixels[i]), scale);
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
    auto range = exposure_range(reference, options, &test);
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
