// FLIP on the device (flip/device_flip.h) against the CPU code it mirrors (flip.h, hdr_flip.h):
// per-pixel maps within 1e-5 and means within 1e-6 relative, on random, structured and real
// content, at odd sizes (1x1, 3x7, 1921x1081) and at several ppd; identical images give 0; bad
// input is refused as the CPU code refuses it. On lavapipe (or $KDOP_DEVICE) with the validation
// layer on and no message.
#include "flip/device_flip.h"
#include "flip/hdr_flip.h"
#include "images/texture_cases.h"
#include "runtime/rectify_pass.h"
#include "temporal/taa_measure.h"
#include "tests/gpu_support.h"

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <glm/common.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

namespace kdop {
namespace {

constexpr double kPpd = 67.02064327658226; // the default viewing conditions
constexpr double kMapTolerance = 1e-5, kMeanTolerance = 1e-6;

std::unique_ptr<DeviceFlip> device_flip(double ppd, std::uint32_t w, std::uint32_t h) {
    auto flip = DeviceFlip::create(test::gpu(), ppd, w, h);
    if (!flip) ADD_FAILURE() << flip.error().message;
    return flip ? std::move(*flip) : nullptr;
}

// Independent uniform noise in [0, 1]: every pixel an edge.
Image noise(std::uint32_t seed, std::uint32_t w, std::uint32_t h) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Image image(w, h);
    for (glm::vec4& p : image.pixels) p = {unit(random), unit(random), unit(random), 1};
    return image;
}

// Smooth shapes: a color gradient with a disc on it, the test's disc moved and its colors
// perturbed: large flat parts, a few edges, small and large errors.
Image shapes(std::uint32_t seed, std::uint32_t w, std::uint32_t h, float shift) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> small(-0.02f, 0.02f);
    Image image(w, h);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) {
            const float u = (float(x) + 0.5f) / float(w), v = (float(y) + 0.5f) / float(h);
            const float dx = u - 0.5f - shift, dy = v - 0.5f;
            const bool disc = dx * dx + dy * dy < 0.06f;
            const glm::vec3 c = disc ? glm::vec3(0.9f, 0.2f, 0.1f) : glm::vec3(u, v, 0.5f * (u + v));
            image.at(x, y) = glm::vec4(glm::clamp(c + glm::vec3(small(random)), 0.0f, 1.0f), 1.0f);
        }
    return image;
}

// A real game texture (colobot-common-textures, installed by install-deps.sh) and the same
// texture one pixel to the right, slightly darker: what a resolve's small errors look like.
std::pair<Image, Image> real_pair(std::uint32_t w, std::uint32_t h) {
    Image reference(w, h);
    for (const RealTexture& t : installed_real_textures())
        if (t.name == "colobot-grass") reference = load_real_texture(t, w, h);
    Image test = reference;
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) test.at(x, y) = reference.at(x > 0 ? x - 1 : 0, y) * glm::vec4(0.97f);
    return {reference, test};
}

struct Difference {
    double largest = 0;
    std::size_t where = 0;
};
Difference largest_difference(const std::vector<float>& a, const std::vector<float>& b) {
    Difference d;
    EXPECT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        const double e = std::abs(double(a[i]) - double(b[i]));
        if (!(e <= d.largest)) d = {e, i}; // NaN is the largest
    }
    return d;
}

double relative(double a, double b) { return a == b ? 0.0 : std::abs(a - b) / std::max(std::abs(a), std::abs(b)); }

void expect_quiet_validation() {
    for (const std::string& message : test::gpu().validation_messages()) ADD_FAILURE() << "validation: " << message;
}

// The device's LDR-FLIP of one pair against LdrFlip's, map by map and the mean.
void expect_ldr_agrees(const Image& reference, const Image& test, double ppd, const std::string& what) {
    SCOPED_TRACE(what);
    auto device = device_flip(ppd, reference.width, reference.height);
    ASSERT_TRUE(device);
    const LdrFlip cpu(ppd);
    auto expected = cpu.terms(reference, test);
    ASSERT_TRUE(expected) << expected.error().message;
    auto got = device->terms(reference, test);
    ASSERT_TRUE(got) << got.error().message;
    for (auto [name, e, g] :
         {std::tuple{"error", &expected->error, &got->error}, std::tuple{"color", &expected->color, &got->color},
          std::tuple{"feature", &expected->feature, &got->feature}}) {
        const Difference d = largest_difference(*e, *g);
        EXPECT_LE(d.largest, kMapTolerance)
            << name << " map at pixel (" << d.where % reference.width << ", " << d.where / reference.width << "): CPU "
            << (*e)[d.where] << ", device " << (*g)[d.where];
    }
    const double cpu_mean = mean_error(expected->error);
    auto mean = device->mean(reference, test);
    ASSERT_TRUE(mean) << mean.error().message;
    EXPECT_LE(relative(*mean, cpu_mean), kMeanTolerance) << "CPU mean " << cpu_mean << ", device " << *mean;
    EXPECT_GT(cpu_mean, 0.0); // the pair differs, so the agreement is not the trivial 0 = 0
}

TEST(DeviceFlip, LdrMapsAreTheCpusAtOddSizes) {
    expect_ldr_agrees(noise(1, 1, 1), noise(2, 1, 1), kPpd, "1x1 noise");
    expect_ldr_agrees(noise(3, 3, 7), noise(4, 3, 7), kPpd, "3x7 noise");
    expect_ldr_agrees(shapes(5, 7, 3, 0.0f), shapes(6, 7, 3, 0.2f), kPpd, "7x3 shapes");
    expect_ldr_agrees(shapes(7, 1921, 1081, 0.0f), shapes(8, 1921, 1081, 0.01f), kPpd, "1921x1081 shapes");
    expect_quiet_validation();
}

TEST(DeviceFlip, LdrMapsAreTheCpusAtSeveralPpd) {
    for (double ppd : {1.0, 9.5, 40.0, kPpd, 150.0}) {
        expect_ldr_agrees(shapes(9, 97, 61, 0.0f), shapes(10, 97, 61, 0.05f), ppd, fmt::format("shapes, {} ppd", ppd));
        expect_ldr_agrees(noise(11, 45, 38), noise(12, 45, 38), ppd, fmt::format("noise, {} ppd", ppd));
    }
    expect_quiet_validation();
}

TEST(DeviceFlip, LdrMapsAreTheCpusOnARealTexture) {
    const auto [reference, test] = real_pair(320, 180);
    expect_ldr_agrees(reference, test, kPpd, "colobot-grass, shifted and darkened");
    expect_quiet_validation();
}

TEST(DeviceFlip, HdrMapsAreTheCpus) {
    // A gradient over decades of luminance, noise on it; the test's noise differs.
    auto hdr = [](std::uint32_t seed, std::uint32_t w, std::uint32_t h) {
        Image image = noise(seed, w, h);
        for (std::uint32_t y = 0; y < h; ++y)
            for (std::uint32_t x = 0; x < w; ++x)
                image.at(x, y) *= glm::vec4(glm::vec3(std::exp2(10.0f * float(x) / float(w) - 5.0f)), 1.0f);
        return image;
    };
    const Image reference = hdr(21, 53, 29), test = hdr(22, 53, 29);
    const HdrFlip cpu(kPpd);
    auto device = device_flip(kPpd, 53, 29);
    ASSERT_TRUE(device);
    for (ToneMapper mapper : {ToneMapper::aces, ToneMapper::hable, ToneMapper::reinhard}) {
        SCOPED_TRACE(to_string(mapper));
        ExposureOptions options;
        options.tone_mapper = mapper;
        auto expected = cpu.maps(reference, test, options);
        ASSERT_TRUE(expected) << expected.error().message;
        auto got = device->hdr(reference, test, options);
        ASSERT_TRUE(got) << got.error().message;
        EXPECT_EQ(got->range.start, expected->range.start);
        EXPECT_EQ(got->range.stop, expected->range.stop);
        EXPECT_EQ(got->range.count, expected->range.count);
        EXPECT_GE(expected->range.count, 5); // a real range, so the maximum over exposures is exercised
        const Difference d = largest_difference(expected->error, got->error);
        EXPECT_LE(d.largest, kMapTolerance) << "at pixel " << d.where;
        // Which exposure gave a pixel's error can differ only where two exposures' errors are closer
        // than the maps' agreement; here that is never.
        std::size_t same = 0;
        for (std::size_t i = 0; i < expected->exposure.size(); ++i) same += expected->exposure[i] == got->exposure[i];
        EXPECT_EQ(same, expected->exposure.size());
        EXPECT_LE(relative(got->mean, expected->mean), kMeanTolerance);
        auto mean_only = device->hdr(reference, test, options, false);
        ASSERT_TRUE(mean_only) << mean_only.error().message;
        EXPECT_EQ(mean_only->mean, got->mean);
        EXPECT_TRUE(mean_only->error.empty());
    }
    expect_quiet_validation();
}

// HDR-FLIP's exposure range of an image on the device alone: its luminances found there are
// luminances_of's (flip/hdr_flip.h) to the bit, over decades of luminance, with ties, with -0,
// where at least half the pixels are black (the median of the others) and where all are; and a
// pair measured as loaded gives the figures, range and maps of the same pair from the host,
// including a black reference (the range from the test image) and two black images.
TEST(DeviceFlip, LoadedHdrImagesGiveTheHostsExposureRange) {
    constexpr std::uint32_t w = 41, h = 23; // 943 pixels: an odd count, so the median is one value
    auto device = device_flip(kPpd, w, h);
    ASSERT_TRUE(device);
    std::mt19937 random(5);
    std::uniform_real_distribution<float> stops(-30.0f, 30.0f);
    auto spread = [&] {
        Image image = noise(random(), w, h);
        for (glm::vec4& p : image.pixels) p *= glm::vec4(glm::vec3(std::exp2(stops(random))), 1.0f);
        return image;
    };
    Image ties = spread();
    for (std::size_t i = 0; i < ties.pixels.size(); i += 2) ties.pixels[i] = {0.25f, 0.5f, 0.125f, 1.0f};
    Image half_black = spread();
    for (std::size_t i = 0; i < half_black.pixels.size(); i += 3) half_black.pixels[i] = {0, 0, 0, 1};
    for (std::size_t i = 1; i < half_black.pixels.size(); i += 3) half_black.pixels[i] = {-0.0f, -0.0f, -0.0f, 1};
    Image black(w, h);
    for (glm::vec4& p : black.pixels) p = {0, 0, 0, 1};
    const struct {
        const char* what;
        Image reference, test;
    } cases[] = {{"spread", spread(), spread()},
                 {"ties", ties, spread()},
                 {"half black", half_black, spread()},
                 {"black reference", black, spread()},
                 {"both black", black, black}};
    for (const auto& c : cases) {
        SCOPED_TRACE(c.what);
        ExposureOptions fixed; // both ends given: nothing derived while the pair is uploaded
        fixed.start = 0.0f;
        fixed.stop = 1.0f;
        ASSERT_TRUE(device->hdr(c.reference, c.test, fixed, false));
        for (auto [input, image] :
             {std::pair{DeviceFlip::Input::reference, &c.reference}, std::pair{DeviceFlip::Input::test, &c.test}}) {
            const Luminances expected = luminances_of(*image);
            auto got = device->luminances(input);
            ASSERT_TRUE(got) << got.error().message;
            EXPECT_EQ(std::bit_cast<std::uint32_t>(got->largest), std::bit_cast<std::uint32_t>(expected.largest));
            EXPECT_EQ(std::bit_cast<std::uint32_t>(got->median), std::bit_cast<std::uint32_t>(expected.median));
            EXPECT_EQ(got->median_of_lit, expected.median_of_lit);
        }
        EXPECT_EQ(luminances_of(c.reference).median_of_lit, std::string(c.what) == "half black");

        const ExposureOptions derived;
        auto expected = device->hdr(c.reference, c.test, derived, true);
        ASSERT_TRUE(expected) << expected.error().message;
        auto from_host = device->hdr(&c.reference, nullptr, derived, true);
        auto loaded = device->hdr(nullptr, nullptr, derived, true);
        for (auto* got : {&from_host, &loaded}) {
            ASSERT_TRUE(*got) << (*got).error().message;
            EXPECT_EQ((*got)->range.start, expected->range.start);
            EXPECT_EQ((*got)->range.stop, expected->range.stop);
            EXPECT_EQ((*got)->range.count, expected->range.count);
            EXPECT_EQ((*got)->range.note, expected->range.note);
            EXPECT_EQ((*got)->mean, expected->mean);
            EXPECT_EQ((*got)->error, expected->error);
            EXPECT_EQ((*got)->exposure, expected->exposure);
        }
    }
    expect_quiet_validation();
}

// A test image of 1e19 (and one whose exposed values overflow float) tone-maps to white as 1e6
// does, on the device as on the CPU, instead of to NaN, which the device scored as black.
TEST(DeviceFlip, HugeValuesScoreAsOnTheCpu) {
    const auto [reference, unused] = real_pair(32, 24);
    const HdrFlip cpu(kPpd);
    auto device = device_flip(kPpd, 32, 24);
    ASSERT_TRUE(device);
    std::vector<double> means;
    for (float value : {1e6f, 1e19f, 3e38f}) {
        const Image test(32, 24, glm::vec4(value, value, value, 1));
        for (ToneMapper mapper : {ToneMapper::aces, ToneMapper::hable, ToneMapper::reinhard}) {
            SCOPED_TRACE(fmt::format("{} at {}", to_string(mapper), value));
            ExposureOptions options;
            options.tone_mapper = mapper;
            auto expected = cpu.maps(reference, test, options);
            ASSERT_TRUE(expected) << expected.error().message;
            auto got = device->hdr(reference, test, options, false);
            ASSERT_TRUE(got) << got.error().message;
            EXPECT_LE(relative(got->mean, expected->mean), kMeanTolerance);
            if (mapper == ToneMapper::aces) means.push_back(got->mean);
        }
    }
    EXPECT_NEAR(means[1], means[0], 1e-6) << "1e19 is as white as 1e6";
    EXPECT_NEAR(means[2], means[0], 1e-6);
    expect_quiet_validation();
}

// A reference kept from the evaluation before (the same DeviceFlip::ReferenceKey: its upload and
// horizontal filters skipped) gives every map and mean bit for bit as evaluated afresh, over tests
// that differ, with another reference, an HDR-FLIP of several exposures and a refused pair in
// between. And it is kept: a reference changed against the key's promise still scores as the old
// one.
TEST(DeviceFlip, AKeptReferenceGivesTheFiguresOfAFreshOne) {
    constexpr std::uint32_t w = 67, h = 43;
    const Image reference = shapes(21, w, h, 0.0f), other = shapes(22, w, h, 0.1f);
    const Image tests[] = {shapes(23, w, h, 0.03f), noise(24, w, h), shapes(25, w, h, -0.05f)};
    auto fresh = device_flip(kPpd, w, h), kept = device_flip(kPpd, w, h);
    ASSERT_TRUE(fresh && kept);
    constexpr DeviceFlip::ReferenceKey kReference = 7, kNone = DeviceFlip::kNoKey;
    auto expect_same = [&](const Image& ref, const Image& test, DeviceFlip::ReferenceKey how, const std::string& what) {
        SCOPED_TRACE(what);
        auto expected = fresh->ldr(ref, test, true);
        auto got = kept->ldr(ref, test, true, how);
        ASSERT_TRUE(expected && got);
        EXPECT_EQ(got->mean, expected->mean);
        EXPECT_EQ(got->error, expected->error);
    };
    expect_same(reference, tests[0], kReference, "nothing to keep yet");
    expect_same(reference, tests[1], kReference, "kept");
    expect_same(reference, tests[2], kReference, "kept again");
    expect_same(other, tests[0], kNone, "another reference");
    expect_same(reference, tests[1], kReference, "after another reference");
    Image bright = reference;
    for (glm::vec4& p : bright.pixels) p *= glm::vec4(glm::vec3(40.0f), 1.0f);
    ASSERT_TRUE(kept->hdr(bright, tests[0], {}, false));
    expect_same(reference, tests[2], kReference, "after HDR-FLIP's exposures");
    Image negative = tests[0];
    negative.at(3, 2).g = -1.0f;
    EXPECT_FALSE(kept->ldr(reference, negative, false, kReference));
    expect_same(reference, tests[0], kReference, "after a refused pair");

    constexpr DeviceFlip::ReferenceKey kChanged = 8; // one key, kept, then its pixels changed behind it
    auto first = kept->ldr(reference, tests[1], false, kChanged);
    ASSERT_TRUE(first);
    auto stale = kept->ldr(other, tests[1], false, kChanged);
    auto honest = kept->ldr(other, tests[1], false);
    ASSERT_TRUE(stale && honest);
    EXPECT_EQ(stale->mean, first->mean) << "the planes of the reference kept";
    EXPECT_NE(honest->mean, first->mean);
    expect_quiet_validation();
}

// An image loaded from a texture on the device (a resolve's output, measured where it is) is
// what within_range (temporal/taa_measure.h) makes of it on the host, bit for bit: values within
// rounding of the range moved onto it, -0 kept. One with values further out, NaN or (HDR) infinite
// is counted, its first pixel in row-major order found, and that pixel's values give the host's
// message word for word.
TEST(DeviceFlip, ALoadedOutputIsWhatWithinRangeMakesOfIt) {
    constexpr std::uint32_t w = 37, h = 11;
    auto device = device_flip(kPpd, w, h);
    auto pass = RectifyPass::create(test::gpu(), w, h, TextureFormat::rgba32f, std::vector<std::string>{"output"});
    ASSERT_TRUE(device && pass);
    auto load = [&](const Image& image, ColorRange range) -> Result<std::optional<DeviceFlip::Outside>> {
        const Image* images[] = {&image};
        if (auto ok = (*pass)->upload(images); !ok) return std::unexpected(ok.error());
        auto view = (*pass)->view_to_sample("output");
        if (!view) return std::unexpected(view.error());
        return device->load(DeviceFlip::Input::test, *view, range == ColorRange::hdr, kOutputRounding);
    };
    for (ColorRange range : {ColorRange::ldr, ColorRange::hdr}) {
        const bool hdr = range == ColorRange::hdr;
        SCOPED_TRACE(hdr ? "hdr" : "ldr");
        Image image = noise(31, w, h);
        for (glm::vec4& p : image.pixels) p *= glm::vec4(glm::vec3(hdr ? 50.0f : 1.0f), 1.0f);
        image.at(0, 0) = {-5e-5f, 1.00005f, -0.0f, 0.5f}; // rounding both ways
        image.at(1, 0) = {0.0f, 1.0f, 1e-30f, 1.0f};
        image.at(2, 0) = {-2e-3f, 40.0f, 1.0f, 1.0f}; // HDR: within rounding of a bright pixel
        auto expected = within_range(image, range, "out");
        if (!hdr) {
            EXPECT_FALSE(expected) << "LDR: (2, 0) lies outside";
            image.at(2, 0) = {0.5f, 0.5f, 0.5f, 1.0f};
            expected = within_range(image, range, "out");
        }
        ASSERT_TRUE(expected) << expected.error().message;
        auto loaded = load(image, range);
        ASSERT_TRUE(loaded) << loaded.error().message;
        EXPECT_FALSE(*loaded);
        const Image got = device->loaded(DeviceFlip::Input::test);
        EXPECT_EQ(std::memcmp(got.pixels.data(), expected->pixels.data(), got.pixels.size() * sizeof(glm::vec4)), 0);
        EXPECT_TRUE(std::signbit(got.at(0, 0).b)) << "-0 kept";

        const float bad[] = {hdr ? -0.01f : 1.01f, NAN, hdr ? INFINITY : -0.5f};
        for (float value : bad) {
            Image outside = image;
            outside.at(30, 9).g = value;
            outside.at(4, 6).b = value;
            outside.at(9, 6).r = value;
            auto message = within_range(outside, range, "out");
            ASSERT_FALSE(message) << value;
            auto found = load(outside, range);
            ASSERT_TRUE(found) << found.error().message;
            ASSERT_TRUE(*found) << value << " passed";
            EXPECT_EQ((*found)->count, 3u) << value;
            EXPECT_EQ((*found)->x, 4u);
            EXPECT_EQ((*found)->y, 6u);
            EXPECT_EQ(outside_range((*found)->value, range, "out", (*found)->x, (*found)->y),
                      std::optional(message.error().message))
                << value;
        }
    }
    expect_quiet_validation();
}

TEST(DeviceFlip, IdenticalImagesGiveZero) {
    const auto [reference, test] = real_pair(64, 48);
    auto device = device_flip(kPpd, 64, 48);
    ASSERT_TRUE(device);
    auto ldr = device->terms(reference, reference);
    ASSERT_TRUE(ldr) << ldr.error().message;
    EXPECT_EQ(*std::max_element(ldr->error.begin(), ldr->error.end()), 0.0f);
    Image bright = reference;
    for (glm::vec4& p : bright.pixels) p *= glm::vec4(glm::vec3(40.0f), 1.0f);
    auto hdr = device->hdr(bright, bright, {});
    ASSERT_TRUE(hdr) << hdr.error().message;
    EXPECT_EQ(hdr->mean, 0.0);
    EXPECT_EQ(*std::max_element(hdr->error.begin(), hdr->error.end()), 0.0f);
    expect_quiet_validation();
}

TEST(DeviceFlip, RefusesBadInputNamingIt) {
    auto device = device_flip(kPpd, 5, 4);
    ASSERT_TRUE(device);
    const Image good = noise(31, 5, 4);
    auto message = [](const auto& result) { return result ? std::string("(accepted)") : result.error().message; };

    EXPECT_EQ(message(device->mean(good, noise(32, 4, 5))),
              "test image: 4x5, but this FLIP evaluator was made for 5x4");
    Image nan = good;
    nan.at(2, 3).g = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(message(device->mean(good, nan)).find("test image: pixel (2, 3) has green = nan"), std::string::npos)
        << message(device->mean(good, nan));
    Image above = good;
    above.at(1, 0).r = 1.5f;
    EXPECT_NE(message(device->mean(above, good)).find("reference image: pixel (1, 0) has red = 1.5"),
              std::string::npos);
    Image negative = good;
    negative.at(4, 1).b = -0.25f;
    EXPECT_NE(message(device->hdr(good, negative, {})).find("test image: pixel (4, 1) has B = -0.25"),
              std::string::npos);
    ExposureOptions reversed;
    reversed.start = 2.0f;
    reversed.stop = -1.0f;
    EXPECT_EQ(message(device->hdr(good, good, reversed)), "the start exposure 2 is above the stop exposure -1");

    EXPECT_FALSE(DeviceFlip::create(test::gpu(), 0.5, 5, 4));
    EXPECT_FALSE(DeviceFlip::create(test::gpu(), kPpd, 0, 4));
    expect_quiet_validation();
}

} // namespace
} // namespace kdop
