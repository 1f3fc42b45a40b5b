// HDR-FLIP (flip/hdr_flip.h): the exposure range as NVlabs/flip derives it, on cases worked here by
// hand; the error as the largest LDR-FLIP over the tone-mapped exposures; zero for identical images;
// kdop flip --hdr; bad input refused with the image, pixel or argument named.
#include "flip/hdr_flip.h"
#include "images/image_io.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <glm/common.hpp>

#include <cmath>
#include <filesystem>
#include <random>

namespace kdop {
namespace {

namespace fs = std::filesystem;

constexpr double kPpd = 67.02064327658226; // the default viewing conditions

// Seeded HDR content: a gradient over decades of luminance with noise on it.
Image hdr_image(std::uint32_t seed, std::uint32_t w, std::uint32_t h, float scale = 1.0f) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Image image(w, h);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) {
            const float base = scale * std::exp2(8.0f * float(x) / float(w) - 4.0f); // 1/16 .. 16
            image.at(x, y) = {base * (0.5f + unit(random)), base * (0.5f + unit(random)), base * unit(random), 1};
        }
    return image;
}

// A gray image of these values, row-major: its luminance is the value.
Image gray(std::uint32_t w, std::uint32_t h, std::vector<float> values) {
    Image image(w, h);
    for (std::size_t i = 0; i < values.size(); ++i) image.pixels[i] = glm::vec4(glm::vec3(values[i]), 1);
    return image;
}

// The larger root of T(x) = 0.85 for a curve (a x^2 + b x + c) / (d x^2 + e x + f), by the usual
// formula in double: the tone mappers' coefficients are NVlabs/flip's (ToneMappingCoefficients).
double x_for_85_percent(double a, double b, double c, double d, double e, double f) {
    const double qa = a - 0.85 * d, qb = b - 0.85 * e, qc = c - 0.85 * f;
    if (qa == 0) return -qc / qb;
    return (-qb + std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
}
const double kAcesX = x_for_85_percent(0.36 * 2.51, 0.6 * 0.03, 0, 0.36 * 2.43, 0.6 * 0.59, 0.14);
const double kHableX = x_for_85_percent(0.231683, 0.013791, 0, 0.18, 0.3, 0.018);
const double kReinhardX = 0.85 / 0.15; // x / (x + 1) = 0.85

TEST(HdrFlip, ExposureRangeIsTheReferencesOnCasesWorkedByHand) {
    struct Case {
        Image reference;
        ToneMapper tone_mapper;
        double x, largest, median;
        int count;
    };
    const Case cases[] = {
        // 2x2 of 1, 2, 4, 8: the median is the element at 4 / 2 = 2 sorted, 4; one stop apart, so 2 exposures.
        {gray(2, 2, {8, 1, 4, 2}), ToneMapper::aces, kAcesX, 8, 4, 2},
        {gray(2, 2, {8, 1, 4, 2}), ToneMapper::hable, kHableX, 8, 4, 2},
        {gray(2, 2, {8, 1, 4, 2}), ToneMapper::reinhard, kReinhardX, 8, 4, 2},
        // 3 pixels: the median is index 1 sorted, 0.75; log2(64 / 0.75) = 6.4 stops, so 7 exposures.
        {gray(3, 1, {64, 0.25f, 0.75f}), ToneMapper::aces, kAcesX, 64, 0.75, 7},
        // Zeros count in the median (at index 2 of 0, 0, 1, 3): 1.
        {gray(4, 1, {0, 3, 0, 1}), ToneMapper::aces, kAcesX, 3, 1, 2},
    };
    for (const Case& c : cases) {
        auto range = exposure_range(c.reference, {c.tone_mapper, {}, {}, {}});
        ASSERT_TRUE(range) << range.error().message;
        EXPECT_NEAR(range->start, std::log2(c.x / c.largest), 2e-6) << to_string(c.tone_mapper);
        EXPECT_NEAR(range->stop, std::log2(c.x / c.median), 2e-6) << to_string(c.tone_mapper);
        EXPECT_EQ(range->count, c.count) << to_string(c.tone_mapper);
    }
    // ACES maps 2.1188 to 0.85 (Narkowicz's fit with the 0.6 pre-exposure cancelled).
    EXPECT_NEAR(kAcesX, 2.1188, 1e-4);
    EXPECT_NEAR(tone_map(ToneMapper::aces, glm::vec3(float(kAcesX))).x, 0.85, 1e-6);
    EXPECT_NEAR(tone_map(ToneMapper::hable, glm::vec3(float(kHableX))).x, 0.85, 1e-6);
    EXPECT_NEAR(tone_map(ToneMapper::reinhard, glm::vec3(float(kReinhardX))).x, 0.85, 1e-6);
    EXPECT_NEAR(tone_map(ToneMapper::reinhard, glm::vec3(1, 0, 0)).r, 1 / 1.2126, 1e-6)
        << "Reinhard divides by 1 + luminance, per pixel, not per channel";

    // Given values are kept; the exposures step evenly from start to stop.
    auto given = exposure_range(gray(1, 1, {1}), {ToneMapper::aces, -3.0f, 1.0f, 5});
    ASSERT_TRUE(given);
    EXPECT_EQ(given->start, -3.0f);
    EXPECT_EQ(given->stop, 1.0f);
    EXPECT_EQ(given->count, 5);
    for (int i = 0; i < 5; ++i) EXPECT_EQ(given->exposure(i), -3.0f + float(i));
    auto counted = exposure_range(gray(1, 1, {1}), {ToneMapper::aces, -3.0f, 0.5f, {}});
    ASSERT_TRUE(counted);
    EXPECT_EQ(counted->count, 4) << "ceil(3.5)";
    auto one = exposure_range(gray(1, 1, {1}), {ToneMapper::aces, 0.5f, 2.0f, 1});
    ASSERT_TRUE(one);
    EXPECT_EQ(one->exposure(0), 0.5f) << "one exposure is the start exposure";
}

TEST(HdrFlip, RefusesRangesThatCannotBeEvaluated) {
    struct Case {
        Image reference;
        ExposureOptions options;
        std::string message;
    };
    const Case cases[] = {
        {gray(2, 1, {1, 2}), {ToneMapper::aces, 2.0f, 1.0f, {}}, "the start exposure 2 is above the stop exposure 1"},
        {gray(2, 1, {1, 2}), {ToneMapper::aces, 5.0f, {}, {}}, "derived from the reference"},
        {gray(2, 1, {1, 2}), {ToneMapper::aces, {}, {}, 0}, "0 exposures: HDR-FLIP needs at least 1"},
        {gray(2, 1, {0, 0}), {}, "largest luminance is 0"},
        // 2^133 is not a float: a reference of 1e-40 (and one of 1e38, at -126.6 stops) is refused.
        {gray(2, 1, {1e-40f, 1e-40f}), {}, "the reference's largest luminance 1e-40 puts an exposure at 134.0 stops"},
        {gray(2, 1, {3e38f, 3e38f}), {}, "the reference's largest luminance 3e+38 puts an exposure at -126.7 stops"},
        {gray(2, 1, {1, 2}), {ToneMapper::aces, -200.0f, 1.0f, {}}, "reaches beyond the 126 stops"},
    };
    for (const Case& c : cases) {
        auto range = exposure_range(c.reference, c.options);
        ASSERT_FALSE(range) << c.message;
        EXPECT_NE(range.error().message.find(c.message), std::string::npos) << range.error().message;
    }
    // A black reference is measured once both ends are given.
    EXPECT_TRUE(exposure_range(gray(2, 1, {0, 0}), {ToneMapper::aces, -1.0f, 1.0f, {}}));
}

// Where NVlabs/flip's derivation divides by zero, kdop defines the range and says so in its note.
TEST(HdrFlip, DefinesTheRangeOfBlackAndMostlyBlackReferences) {
    // At least half black: the stop exposure is from the median of the others (2 of 1, 2, 4).
    auto dark = exposure_range(gray(7, 1, {0, 0, 0, 0, 1, 4, 2}), {ToneMapper::aces, {}, {}, {}});
    ASSERT_TRUE(dark) << dark.error().message;
    EXPECT_NEAR(dark->start, std::log2(kAcesX / 4), 2e-6);
    EXPECT_NEAR(dark->stop, std::log2(kAcesX / 2), 2e-6);
    EXPECT_NE(dark->note.find("at least half of the reference's pixels are black"), std::string::npos) << dark->note;
    // A black reference takes the test image's range; a black pair is measured at exposure 0.
    const Image black = gray(2, 2, {0, 0, 0, 0}), lit = gray(2, 2, {8, 1, 4, 2});
    auto from_test = exposure_range(black, {}, &lit);
    ASSERT_TRUE(from_test) << from_test.error().message;
    EXPECT_NEAR(from_test->start, std::log2(kAcesX / 8), 2e-6);
    EXPECT_NEAR(from_test->stop, std::log2(kAcesX / 4), 2e-6);
    EXPECT_NE(from_test->note.find("the reference is black"), std::string::npos) << from_test->note;
    auto both = exposure_range(black, {}, &black);
    ASSERT_TRUE(both) << both.error().message;
    EXPECT_EQ(both->count, 1);
    EXPECT_EQ(both->exposure(0), 0.0f);
    EXPECT_NE(both->note.find("both images are black"), std::string::npos) << both->note;
    auto maps = HdrFlip(kPpd).maps(black, black, {});
    ASSERT_TRUE(maps) << maps.error().message;
    EXPECT_EQ(maps->mean, 0.0);
    // A note only where the derivation departs from the reference code's.
    auto plain = exposure_range(lit, {}, &black);
    ASSERT_TRUE(plain);
    EXPECT_TRUE(plain->note.empty()) << plain->note;
}

// 1e19 squared is beyond float: the tone curves' limit forms take it, and an exposed value that
// overflowed, to white as they take 1e6, on the CPU as on the device (device_flip_test.cpp).
TEST(HdrFlip, HugeValuesToneMapToWhiteAsLargeOnesDo) {
    for (ToneMapper t : {ToneMapper::aces, ToneMapper::hable, ToneMapper::reinhard})
        for (float scale : {1.0f, 1e30f}) {
            const glm::vec3 huge = tone_map(t, glm::vec3(1e19f, 1e19f, 1e19f), scale);
            const glm::vec3 large = tone_map(t, glm::vec3(1e6f), 1.0f);
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(huge[c])) << to_string(t) << " at scale " << scale;
                EXPECT_NEAR(std::clamp(huge[c], 0.0f, 1.0f), std::clamp(large[c], 0.0f, 1.0f), 1e-5) << to_string(t);
            }
        }
    // Reinhard keeps the hue of an overflowing color: the limit is color / luminance.
    const glm::vec3 red = tone_map(ToneMapper::reinhard, glm::vec3(3e38f, 1e38f, 0.0f), 1e10f);
    EXPECT_NEAR(red.g, 1.0f / (0.2126f * 3 + 0.7152f), 1e-5);
    EXPECT_EQ(red.b, 0.0f);
    // The test image of 1e19 scores as the one of 1e6 against any reference, not as black.
    const Image reference = hdr_image(5, 24, 16);
    const HdrFlip flip(kPpd);
    auto huge = flip.maps(reference, gray(24, 16, std::vector<float>(24 * 16, 1e19f)), {});
    auto large = flip.maps(reference, gray(24, 16, std::vector<float>(24 * 16, 1e6f)), {});
    auto black = flip.maps(reference, gray(24, 16, std::vector<float>(24 * 16, 0.0f)), {});
    ASSERT_TRUE(huge && large && black);
    EXPECT_NEAR(huge->mean, large->mean, 1e-6);
    EXPECT_GT(std::abs(huge->mean - black->mean), 0.02);
}

TEST(HdrFlip, IsTheLargestLdrFlipOverTheToneMappedExposures) {
    const Image reference = hdr_image(1, 37, 23), test = hdr_image(2, 37, 23, 1.1f);
    const HdrFlip flip(kPpd);
    for (ToneMapper t : {ToneMapper::aces, ToneMapper::hable, ToneMapper::reinhard}) {
        auto maps = flip.maps(reference, test, {t, {}, {}, {}});
        ASSERT_TRUE(maps) << maps.error().message;
        ASSERT_GE(maps->range.count, 2);
        std::vector<float> largest(reference.pixels.size(), 0.0f), which(reference.pixels.size(), 0.0f);
        for (int i = 0; i < maps->range.count; ++i) {
            const float e =
                maps->range.start + float(i) * (maps->range.stop - maps->range.start) / float(maps->range.count - 1);
            ASSERT_EQ(maps->range.exposure(i), e);
            // Exposed, tone mapped and clamped here, independently of HdrFlip::tone_mapped.
            Image r(reference.width, reference.height), s(reference.width, reference.height);
            for (std::size_t p = 0; p < r.pixels.size(); ++p) {
                r.pixels[p] = glm::vec4(
                    glm::clamp(tone_map(t, glm::vec3(reference.pixels[p]) * std::pow(2.0f, e)), 0.0f, 1.0f), 1);
                s.pixels[p] =
                    glm::vec4(glm::clamp(tone_map(t, glm::vec3(test.pixels[p]) * std::pow(2.0f, e)), 0.0f, 1.0f), 1);
            }
            auto ldr = flip.ldr().error_map(r, s);
            ASSERT_TRUE(ldr) << ldr.error().message;
            for (std::size_t p = 0; p < ldr->size(); ++p)
                if ((*ldr)[p] > largest[p]) {
                    largest[p] = (*ldr)[p];
                    which[p] = float(i) / float(maps->range.count - 1);
                }
        }
        EXPECT_EQ(maps->error, largest) << to_string(t);
        EXPECT_EQ(maps->exposure, which) << to_string(t);
        EXPECT_GT(mean_error(maps->error), 0.01) << to_string(t);
    }
}

// With one exposure, HDR-FLIP is the LDR-FLIP of the pair tone mapped at it; here the pair's values
// all lie in [0, 1] after tone mapping, so the clamp changes nothing.
TEST(HdrFlip, OneExposureIsTheLdrFlipOfTheToneMappedPair) {
    const Image reference = hdr_image(3, 24, 16), test = hdr_image(4, 24, 16);
    const HdrFlip flip(kPpd);
    const float exposure = -1.5f;
    auto maps = flip.maps(reference, test, {ToneMapper::aces, exposure, exposure, 1});
    ASSERT_TRUE(maps) << maps.error().message;
    const Image r = HdrFlip::tone_mapped(reference, ToneMapper::aces, exposure);
    const Image s = HdrFlip::tone_mapped(test, ToneMapper::aces, exposure);
    for (const Image* image : {&r, &s})
        for (std::size_t p = 0; p < image->pixels.size(); ++p)
            for (int c = 0; c < 3; ++c) {
                const float unclamped =
                    tone_map(ToneMapper::aces,
                             glm::vec3((image == &r ? reference : test).pixels[p]) * std::pow(2.0f, exposure))[c];
                ASSERT_LT(unclamped, 1.0f);
                ASSERT_EQ(image->pixels[p][c], std::max(unclamped, 0.0f));
            }
    EXPECT_EQ(maps->error, *flip.ldr().error_map(r, s));
    EXPECT_EQ(maps->exposure, std::vector<float>(r.pixels.size(), 0.0f));
}

TEST(HdrFlip, IdenticalImagesGiveZero) {
    const Image image = hdr_image(5, 31, 17, 40.0f);
    auto maps = HdrFlip(kPpd).maps(image, image, {});
    ASSERT_TRUE(maps) << maps.error().message;
    EXPECT_EQ(mean_error(maps->error), 0.0);
    for (float e : maps->error) ASSERT_EQ(e, 0.0f);
}

TEST(HdrFlip, RefusesBadImagesNamingThePixel) {
    const Image good = hdr_image(6, 8, 8);
    Image negative = good, nan = good, infinite = good;
    negative.at(3, 2).g = -0.25f;
    nan.at(1, 5).r = std::nanf("");
    infinite.at(7, 0).b = INFINITY;
    const HdrFlip flip(kPpd);
    const std::pair<const Image*, std::string> cases[] = {
        {&negative, "test image: pixel (3, 2) has G = -0.25"},
        {&nan, "test image: pixel (1, 5) has R = nan"},
        {&infinite, "test image: pixel (7, 0) has B = inf"},
    };
    for (const auto& [image, message] : cases) {
        auto maps = flip.maps(good, *image, {});
        ASSERT_FALSE(maps) << message;
        EXPECT_NE(maps.error().message.find(message), std::string::npos) << maps.error().message;
    }
    auto sizes = flip.maps(good, hdr_image(7, 8, 9), {});
    ASSERT_FALSE(sizes);
    EXPECT_NE(sizes.error().message.find("test image: 8x9, but the reference image is 8x8"), std::string::npos);
}

std::string kdop_flip(const std::string& args) { return test::kdop_binary() + " flip " + args; }

TEST(CliHdrFlip, PrintsTheMeanAndWritesBothMaps) {
    test::TempDir dir;
    const Image reference = hdr_image(8, 24, 16), test = hdr_image(9, 24, 16, 1.2f);
    const std::string r_exr = (dir / "reference.exr").string(), t_exr = (dir / "test.exr").string();
    ASSERT_TRUE(write_image(r_exr, reference));
    ASSERT_TRUE(write_image(t_exr, test));
    const std::string inputs = "--reference " + r_exr + " --test " + t_exr + " --hdr";
    auto expected = HdrFlip(kPpd).maps(reference, test, {ToneMapper::hable, {}, {}, {}});
    ASSERT_TRUE(expected);

    const fs::path map = dir / "map.exr", exposures = dir / "exposures.exr";
    const std::string maps = " --tone-mapper hable --out " + map.string() + " --exposure-map " + exposures.string();
    // --cpu: the CPU code's mean and maps exactly.
    auto r = test::run(kdop_flip(inputs + maps + " --cpu"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find(fmt::format("HDR-FLIP mean {} at 67.02 pixels per degree (24x16; hable tone mapper, {} "
                                     "exposures from {:.4g} to {:.4g}) on the CPU",
                                     mean_error(expected->error), expected->range.count, expected->range.start,
                                     expected->range.stop)),
              std::string::npos)
        << r.out;
    auto written = read_image(map.string());
    ASSERT_TRUE(written);
    auto written_exposures = read_image(exposures.string());
    ASSERT_TRUE(written_exposures);
    for (std::size_t i = 0; i < expected->error.size(); ++i) {
        ASSERT_EQ(written->pixels[i].r, expected->error[i]) << i;
        ASSERT_EQ(written_exposures->pixels[i].r, expected->exposure[i]) << i;
    }
    // By default on the device: the same range, the mean within 1e-6 relative, the maps within 1e-5.
    r = test::run(kdop_flip(inputs + maps + " --validation"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
    const std::string range = fmt::format("{} exposures from {:.4g} to {:.4g}) on llvmpipe", expected->range.count,
                                          expected->range.start, expected->range.stop);
    EXPECT_NE(r.out.find(range), std::string::npos) << r.out;
    const std::string prefix = "HDR-FLIP mean ";
    ASSERT_EQ(r.out.find(prefix), 0u) << r.out;
    EXPECT_NEAR(std::stod(r.out.substr(prefix.size())), expected->mean, 1e-6 * expected->mean) << r.out;
    written = read_image(map.string());
    ASSERT_TRUE(written);
    written_exposures = read_image(exposures.string());
    ASSERT_TRUE(written_exposures);
    for (std::size_t i = 0; i < expected->error.size(); ++i) {
        ASSERT_NEAR(written->pixels[i].r, expected->error[i], 1e-5) << i;
        ASSERT_EQ(written_exposures->pixels[i].r, expected->exposure[i]) << i;
    }

    r = test::run(kdop_flip(inputs + " --start-exposure -2 --stop-exposure 1 --exposures 4"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("aces tone mapper, 4 exposures from -2 to 1)"), std::string::npos) << r.out;

    // Refused: a range the other way round, a count of 0, HDR options without --hdr, negative values.
    Image negative = test;
    negative.at(2, 3).r = -1.0f;
    const std::string bad = (dir / "negative.exr").string();
    ASSERT_TRUE(write_image(bad, negative));
    struct Case {
        std::string args;
        int exit_code;
        std::string message;
    };
    const Case cases[] = {
        {inputs + " --start-exposure 2 --stop-exposure 1", 1, "the start exposure 2 is above the stop exposure 1"},
        {inputs + " --exposures 0", 2, "--exposures"},
        {"--reference " + r_exr + " --test " + t_exr + " --tone-mapper hable", 2, "--tone-mapper requires --hdr"},
        {"--reference " + r_exr + " --test " + bad + " --hdr", 1,
         "--test " + bad + ": pixel (2, 3) has R = -1; HDR-FLIP takes finite linear RGB that is not negative"},
        {inputs + " --out " + map.string() + " --exposure-map " + map.string(), 2, "both name"},
    };
    for (const Case& c : cases) {
        const fs::path out = dir / "refused.exr";
        r = test::run(kdop_flip(c.args + (c.args.find("--out") == std::string::npos ? " --out " + out.string() : "")));
        EXPECT_EQ(r.exit_code, c.exit_code) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\nstderr was: " << r.err;
        EXPECT_FALSE(fs::exists(out)) << c.args;
    }
}

} // namespace
} // namespace kdop
