// LDR-FLIP against its definition (Andersson et al. 2020, and NVlabs/flip where the two differ):
// flat images, where no feature exists and the CSF filters change nothing, against the paper's
// color pipeline written out again below in double; a step edge, whose feature error follows
// from the detectors' normalization alone; the viewing distance; symmetry; refused input; and
// `kdop flip` run as a user runs it.
#include "flip/color_spaces.h"
#include "flip/flip.h"
#include "flip/flip_statistics.h"
#include "flip/magma.h"
#include "images/image_io.h"
#include "images/random.h"
#include "tests/test_support.h"

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <thread>

namespace kdop {
namespace {
namespace fs = std::filesystem;

// The paper's color metric for two flat colors, in double, independent of flip/: linear sRGB to
// XYZ (the reference's exact ratios), CIE L*a*b* relative to the white the matrix gives (1, 1, 1),
// the Hunt adjustment, HyAB, the exponent qc = 0.7 and the remapping with pc = 0.4, pt = 0.95 of
// the largest distance, green's to blue's.
namespace paper {

const double kRgbToXyz[3][3] = {{10135552.0 / 24577794, 8788810.0 / 24577794, 4435075.0 / 24577794},
                                {2613072.0 / 12288897, 8788810.0 / 12288897, 887015.0 / 12288897},
                                {1425312.0 / 73733382, 8788810.0 / 73733382, 70074185.0 / 73733382}};

struct Lab {
    double L, a, b;
};

glm::dvec3 xyz(glm::dvec3 rgb) {
    return {kRgbToXyz[0][0] * rgb.r + kRgbToXyz[0][1] * rgb.g + kRgbToXyz[0][2] * rgb.b,
            kRgbToXyz[1][0] * rgb.r + kRgbToXyz[1][1] * rgb.g + kRgbToXyz[1][2] * rgb.b,
            kRgbToXyz[2][0] * rgb.r + kRgbToXyz[2][1] * rgb.g + kRgbToXyz[2][2] * rgb.b};
}
const glm::dvec3 kWhite = xyz({1, 1, 1});

Lab hunt_lab(glm::dvec3 rgb) {
    const glm::dvec3 t = xyz(rgb) / kWhite;
    double f[3];
    for (int i = 0; i < 3; ++i) {
        const double d = 6.0 / 29.0;
        f[i] = t[i] > d * d * d ? std::cbrt(t[i]) : t[i] / (3 * d * d) + 4.0 / 29.0;
    }
    const double L = 116 * f[1] - 16;
    return {L, 0.01 * L * 500 * (f[0] - f[1]), 0.01 * L * 200 * (f[1] - f[2])};
}

// YCxCz, the opponent space the CSF filters work in: L*a*b* without the cube root.
glm::dvec3 ycxcz(glm::dvec3 rgb) {
    const glm::dvec3 t = xyz(rgb) / kWhite;
    return {116 * t.y - 16, 500 * (t.x - t.y), 200 * (t.y - t.z)};
}
glm::dvec3 linear_rgb(glm::dvec3 ycxcz) {
    const double y = (ycxcz.x + 16) / 116;
    const glm::dvec3 xyz = glm::dvec3(y + ycxcz.y / 500, y, y - ycxcz.z / 200) * kWhite;
    const glm::dmat3 to_xyz =
        glm::transpose(glm::dmat3(kRgbToXyz[0][0], kRgbToXyz[0][1], kRgbToXyz[0][2], kRgbToXyz[1][0], kRgbToXyz[1][1],
                                  kRgbToXyz[1][2], kRgbToXyz[2][0], kRgbToXyz[2][1], kRgbToXyz[2][2]));
    return glm::inverse(to_xyz) * xyz;
}

double hyab(Lab p, Lab q) { return std::abs(p.L - q.L) + std::hypot(p.a - q.a, p.b - q.b); }

double cmax() { return std::pow(hyab(hunt_lab({0, 1, 0}), hunt_lab({0, 0, 1})), 0.7); }

double color_error(Lab reference, Lab test) {
    const double d = std::pow(hyab(reference, test), 0.7), pccmax = 0.4 * cmax();
    return d < pccmax ? 0.95 * d / pccmax : 0.95 + (d - pccmax) / (cmax() - pccmax) * 0.05;
}
double color_error(glm::dvec3 reference, glm::dvec3 test) { return color_error(hunt_lab(reference), hunt_lab(test)); }

// The CSF of one channel as a 2-D kernel, S(r) = sum of a sqrt(pi/b) exp(-pi^2 r^2 / b) over its
// Gaussians, r in degrees, on the square of the widest Gaussian's 3 standard deviations,
// normalized to sum 1; summed over y: what it does to an image whose columns are constant.
std::vector<double> csf_profile(std::initializer_list<std::pair<double, double>> gaussians, double ppd) {
    const int r = int(std::ceil(3 * std::sqrt(0.04 / (2 * std::numbers::pi * std::numbers::pi)) * ppd));
    std::vector<double> profile(std::size_t(2 * r + 1), 0.0);
    double total = 0;
    for (int x = -r; x <= r; ++x)
        for (int y = -r; y <= r; ++y) {
            const double r2 = (double(x) * x + double(y) * y) / (ppd * ppd);
            double s = 0;
            for (const auto& [a, b] : gaussians)
                s += a * std::sqrt(std::numbers::pi / b) * std::exp(-std::numbers::pi * std::numbers::pi * r2 / b);
            profile[std::size_t(x + r)] += s;
            total += s;
        }
    for (double& w : profile) w /= total;
    return profile;
}

} // namespace paper

// The float pipeline against the double formulas.
double tolerance(double expected) { return 1e-5 + 1e-4 * expected; }

const double kDefaultPpd = pixels_per_degree(ViewingConditions{});

Image flat(glm::vec3 rgb, std::uint32_t w = 24, std::uint32_t h = 16) { return Image(w, h, glm::vec4(rgb, 1)); }

Image noise(std::uint64_t seed, std::uint32_t w = 40, std::uint32_t h = 30) {
    Image image(w, h);
    Random random(seed);
    for (glm::vec4& p : image.pixels)
        p = {float(random.uniform()), float(random.uniform()), float(random.uniform()), 1};
    return image;
}

// Columns x < edge hold `left`, the others `right`.
Image step(std::uint32_t edge, glm::vec3 left, glm::vec3 right, std::uint32_t w = 64, std::uint32_t h = 12) {
    Image image(w, h);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) image.at(x, y) = glm::vec4(x < edge ? left : right, 1);
    return image;
}

TEST(Flip, DefaultViewingConditionsGiveAbout67PixelsPerDegree) {
    // 0.7 m * (3840 px / 0.7 m) * pi / 180 = 3840 pi / 180 = 67.0206...
    EXPECT_DOUBLE_EQ(kDefaultPpd, 3840 * std::numbers::pi / 180);
    EXPECT_NEAR(kDefaultPpd, 67.02, 0.005);
    // Twice as far, or twice the pixels on the same width: twice the pixels per degree.
    EXPECT_DOUBLE_EQ(pixels_per_degree({1.4, 0.7, 3840}), 2 * kDefaultPpd);
    EXPECT_DOUBLE_EQ(pixels_per_degree({0.7, 0.7, 7680}), 2 * kDefaultPpd);
    EXPECT_DOUBLE_EQ(LdrFlip(kDefaultPpd).pixels_per_degree(), kDefaultPpd);
}

// Radii and normalizations as the paper and the reference define them, at the default 67 ppd.
TEST(Flip, KernelsFollowTheDefinition) {
    const LdrFlip flip(kDefaultPpd);
    const flip::CsfKernels& csf = flip.csf_kernels();
    const flip::FeatureKernels& features = flip.feature_kernels();
    // ceil(3 sqrt(0.04 / (2 pi^2)) 67.02) = ceil(9.05); ceil(3 * 0.5 * 0.082 * 67.02) = ceil(8.24).
    EXPECT_EQ(csf.radius, 10);
    EXPECT_EQ(features.radius, 9);
    EXPECT_NEAR(features.sigma, 0.041 * kDefaultPpd, 1e-12);
    auto full_sum = [](const std::vector<float>& half) {
        double s = half[0];
        for (std::size_t j = 1; j < half.size(); ++j) s += 2.0 * half[j];
        return s;
    };
    EXPECT_NEAR(full_sum(csf.achromatic), 1.0, 1e-6);
    EXPECT_NEAR(full_sum(csf.red_green), 1.0, 1e-6);
    // The 2-D blue-yellow kernel, g1(x) g1(y) + g2(x) g2(y), sums to 1.
    EXPECT_NEAR(std::pow(full_sum(csf.blue_yellow_1), 2) + std::pow(full_sum(csf.blue_yellow_2), 2), 1.0, 1e-6);
    EXPECT_NEAR(full_sum(features.gaussian), 1.0, 1e-6);
    // The edge kernel is antisymmetric: -edge[j] at -j. Its positive weights sum to 1, negative to -1.
    EXPECT_EQ(features.edge[0], 0.0f);
    double positive = 0, negative = 0;
    for (std::size_t j = 1; j < features.edge.size(); ++j) {
        EXPECT_LT(features.edge[j], 0.0f) << j;
        negative += features.edge[j];
        positive -= features.edge[j];
    }
    EXPECT_NEAR(positive, 1.0, 1e-6);
    EXPECT_NEAR(negative, -1.0, 1e-6);
    // The point kernel: negative inside sigma, positive outside, the same normalization.
    positive = negative = 0;
    for (std::size_t j = 0; j < features.point.size(); ++j) {
        const double w = (j == 0 ? 1.0 : 2.0) * features.point[j];
        EXPECT_EQ(w < 0, double(j) < features.sigma) << j;
        (w > 0 ? positive : negative) += w;
    }
    EXPECT_NEAR(positive, 1.0, 1e-6);
    EXPECT_NEAR(negative, -1.0, 1e-6);
}

TEST(Flip, IdenticalImagesGiveExactlyZero) {
    const LdrFlip flip(kDefaultPpd);
    for (const Image& image : {noise(1), flat({0.3f, 0.6f, 0.1f}), step(20, {0, 0, 0}, {1, 1, 1})}) {
        auto map = flip.error_map(image, image);
        ASSERT_TRUE(map) << map.error().message;
        EXPECT_TRUE(std::ranges::all_of(*map, [](float e) { return e == 0.0f; }));
        auto mean = flip.mean(image, image);
        ASSERT_TRUE(mean);
        EXPECT_EQ(*mean, 0.0);
    }
}

// Flat images have no edges or points (dE_f = 0, exactly), and the CSF filters, which sum to 1,
// leave a flat color as it is: every pixel's error is the paper's color error of the two colors.
TEST(Flip, FlatImagesGiveTheRemappedHyabOfTheirColors) {
    const LdrFlip flip(kDefaultPpd);
    const std::pair<glm::vec3, glm::vec3> pairs[] = {
        {{0.5f, 0.5f, 0.5f}, {0.52f, 0.5f, 0.5f}}, {{0.2f, 0.4f, 0.6f}, {0.25f, 0.35f, 0.6f}},
        {{0.9f, 0.1f, 0.1f}, {0.1f, 0.9f, 0.1f}},  {{0.05f, 0.05f, 0.05f}, {0.0f, 0.0f, 0.0f}},
        {{1.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}},  {{0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}},
    };
    // Any size, down to a single pixel: clamp-to-edge makes every image of one color flat.
    const std::pair<std::uint32_t, std::uint32_t> sizes[] = {{24, 16}, {1, 1}, {5, 1}, {1, 7}};
    for (std::size_t p = 0; p < std::size(pairs); ++p) {
        const auto [a, b] = pairs[p];
        const auto [w, h] = sizes[p % std::size(sizes)];
        const double expected = paper::color_error(a, b);
        auto terms = flip.terms(flat(a, w, h), flat(b, w, h));
        ASSERT_TRUE(terms) << terms.error().message;
        for (std::size_t i = 0; i < terms->error.size(); ++i) {
            ASSERT_EQ(terms->feature[i], 0.0f) << i;
            ASSERT_EQ(terms->error[i], terms->color[i]) << i;
            ASSERT_NEAR(terms->error[i], expected, tolerance(expected))
                << fmt::format("({}, {}, {}) vs ({}, {}, {}), pixel {}", a.r, a.g, a.b, b.r, b.g, b.b, i);
        }
    }
    // Green against blue is the largest distance the remapping knows: exactly 1.
    EXPECT_NEAR(*flip.mean(flat({0, 1, 0}), flat({0, 0, 1})), 1.0, 1e-5);
}

TEST(Flip, ErrorGrowsWithThePerturbation) {
    const LdrFlip flip(kDefaultPpd);
    const glm::vec3 base(0.4f, 0.3f, 0.2f);
    double previous = 0;
    for (float d : {0.001f, 0.005f, 0.02f, 0.05f, 0.1f, 0.2f, 0.4f}) {
        const glm::vec3 perturbed = base + glm::vec3(d, -0.5f * d, d);
        auto mean = flip.mean(flat(base), flat(perturbed));
        ASSERT_TRUE(mean) << mean.error().message;
        const double expected = paper::color_error(base, perturbed);
        EXPECT_NEAR(*mean, expected, tolerance(expected)) << d;
        EXPECT_GT(*mean, previous) << d;
        previous = *mean;
    }
}

// Bands of the RGB cube's corners, constant down each column, so that the 2-D filters act as 1-D
// profiles the paper's kernels give directly. The colors filtered with each channel's own CSF
// leave the RGB cube (chroma is blurred wider than luminance: bright pixels beside blue get more
// blue than the cube holds), and the color error is that of the filtered colors clamped to it.
TEST(Flip, ColorTermIsTheCsfFilteredColorsClampedToTheRgbCube) {
    const LdrFlip flip(kDefaultPpd);
    const std::vector<double> y_profile = paper::csf_profile({{1.0, 0.0047}}, kDefaultPpd),
                              cx_profile = paper::csf_profile({{1.0, 0.0053}}, kDefaultPpd),
                              cz_profile = paper::csf_profile({{34.1, 0.04}, {13.5, 0.025}}, kDefaultPpd);
    const int r = int(y_profile.size() / 2);
    const std::uint32_t w = 40, h = 6;
    Image reference(w, h), test(w, h);
    Random random(9);
    glm::vec3 c(0.0f);
    for (std::uint32_t x = 0; x < w; ++x) {
        if (x % 5 == 0) { // bands 5 pixels wide of black, white, the primaries and secondaries
            const std::uint64_t corner = random.next() % 8;
            c = glm::vec3(float(corner & 1), float((corner >> 1) & 1), float((corner >> 2) & 1));
        }
        const glm::vec3 d(float(random.uniform()), float(random.uniform()), float(random.uniform()));
        for (std::uint32_t y = 0; y < h; ++y) reference.at(x, y) = glm::vec4(c, 1), test.at(x, y) = glm::vec4(d, 1);
    }
    auto filtered = [&](const Image& image, int x) {
        glm::dvec3 sum(0.0);
        for (int j = -r; j <= r; ++j) {
            const glm::dvec3 o = paper::ycxcz(glm::dvec3(image.at(std::uint32_t(std::clamp(x + j, 0, int(w) - 1)), 0)));
            const std::size_t k = std::size_t(j + r);
            sum += glm::dvec3(y_profile[k] * o.x, cx_profile[k] * o.y, cz_profile[k] * o.z);
        }
        return paper::linear_rgb(sum);
    };
    auto terms = flip.terms(reference, test);
    ASSERT_TRUE(terms) << terms.error().message;
    int outside = 0;
    for (int x = 0; x < int(w); ++x) {
        const glm::dvec3 a = filtered(reference, x), b = filtered(test, x);
        const auto in_cube = [](glm::dvec3 c) { return glm::all(glm::equal(c, glm::clamp(c, 0.0, 1.0))); };
        outside += !in_cube(a) + !in_cube(b);
        const double expected = paper::color_error(glm::clamp(a, 0.0, 1.0), glm::clamp(b, 0.0, 1.0));
        for (std::uint32_t y = 0; y < h; ++y)
            ASSERT_NEAR(terms->color[y * w + std::uint32_t(x)], expected, tolerance(expected)) << x;
    }
    EXPECT_GT(outside, int(w) / 4); // the clamp matters here
}

// Black is L* = 0 and white L* = 100, both with a* = b* = 0, so their HyAB distance is 100. Green
// and blue are 203.30 apart (Hunt-adjusted L*a*b* (87.74, -75.61, 72.98) and (32.30, 25.58, -34.84)),
// cmax = 203.30^0.7 = 41.276, and 100^0.7 = 25.119 lies above pc cmax = 16.510:
// dE = 0.95 + (25.119 - 16.510) / (41.276 - 16.510) * 0.05 = 0.96738.
TEST(Flip, BlackAgainstWhiteIsTheDefinitionsValue) {
    const double cmax = paper::cmax(), pccmax = 0.4 * cmax;
    const double expected = 0.95 + (std::pow(100.0, 0.7) - pccmax) / (cmax - pccmax) * 0.05;
    EXPECT_NEAR(expected, 0.96738, 1e-5);
    auto mean = LdrFlip(kDefaultPpd).mean(flat({0, 0, 0}), flat({1, 1, 1}));
    ASSERT_TRUE(mean) << mean.error().message;
    EXPECT_NEAR(*mean, expected, 1e-5);
}

// A vertical step from luminance a to b where the test is flat. Beside the step (columns edge - 1
// and edge), the edge detector, whose positive weights sum to 1 and negative ones to -1, answers
// |b - a| exactly, the test nothing, and the point detector less (half the center weight); so
// dE_f = (|b - a| / sqrt 2)^0.5 there, its largest. Farther than the detector's radius, dE_f is
// 0: the error the features add, dE - dE_c = dE_c^(1 - dE_f) - dE_c, lies around the edge only.
TEST(Flip, StepEdgeAddsFeatureErrorAroundTheEdge) {
    const LdrFlip flip(kDefaultPpd);
    const int radius = flip.feature_kernels().radius;
    struct Case {
        float a, b, test;
    };
    for (const Case c : {Case{0.0f, 1.0f, 0.5f}, Case{0.2f, 0.3f, 0.25f}}) {
        const std::uint32_t w = 64, h = 12, edge = 32;
        auto terms = flip.terms(step(edge, glm::vec3(c.a), glm::vec3(c.b), w, h), flat(glm::vec3(c.test), w, h));
        ASSERT_TRUE(terms) << terms.error().message;
        const double beside = std::sqrt(std::abs(c.b - c.a) / std::numbers::sqrt2);
        for (std::uint32_t y = 0; y < h; ++y) {
            float largest_feature = -1;
            std::uint32_t largest_at = 0;
            for (std::uint32_t x = 0; x < w; ++x) {
                const std::size_t i = y * w + x;
                const float color = terms->color[i], feature = terms->feature[i], error = terms->error[i];
                EXPECT_FLOAT_EQ(error, std::pow(color, 1.0f - feature));
                const int distance = x < edge ? int(edge - 1 - x) : int(x - edge); // 0 beside the step
                if (distance == 0) {
                    EXPECT_NEAR(feature, beside, 1e-5) << x;
                    EXPECT_GT(color, 0.0f) << x;
                    EXPECT_GT(error, color) << x;
                }
                if (distance > radius) {
                    EXPECT_EQ(feature, 0.0f) << x;
                    EXPECT_EQ(error, color) << x;
                }
                if (feature > largest_feature) largest_feature = feature, largest_at = x;
            }
            EXPECT_TRUE(largest_at == edge - 1 || largest_at == edge) << largest_at;
        }
        // Far from the step, both images are flat there: the paper's color error of the two colors.
        const double left = paper::color_error(glm::dvec3(c.a), glm::dvec3(c.test));
        const double right = paper::color_error(glm::dvec3(c.b), glm::dvec3(c.test));
        EXPECT_NEAR(terms->error[0], left, tolerance(left));
        EXPECT_NEAR(terms->error[w - 1], right, tolerance(right));
    }
}

// A one-pixel black and white checkerboard against its mean, linear gray 0.5 (YCxCz is linear in
// light, so gray is what full blurring gives). Seen from farther away (more pixels per degree) the
// CSF filters are wider, blur the checkerboard more, and the difference shrinks. Measured away from
// the borders, where clamp-to-edge repeats the last row and column and breaks the pattern.
TEST(Flip, MorePixelsPerDegreeWidenTheCsfAndHideAFinePattern) {
    const std::uint32_t size = 64, margin = 16;
    Image checkerboard(size, size);
    for (std::uint32_t y = 0; y < size; ++y)
        for (std::uint32_t x = 0; x < size; ++x) checkerboard.at(x, y) = glm::vec4(glm::vec3(float((x + y) % 2)), 1);
    const Image gray = flat(glm::vec3(0.5f), size, size);
    auto interior_mean = [&](const std::vector<float>& map) {
        double sum = 0;
        for (std::uint32_t y = margin; y < size - margin; ++y)
            for (std::uint32_t x = margin; x < size - margin; ++x) sum += map[y * size + x];
        return sum / ((size - 2 * margin) * (size - 2 * margin));
    };
    double previous_color = 2, previous_error = 2;
    int previous_radius = 0;
    for (double ppd : {10.0, 20.0, 30.0, 45.0, kDefaultPpd}) {
        const LdrFlip flip(ppd);
        ASSERT_LE(std::max(flip.csf_kernels().radius, flip.feature_kernels().radius), int(margin));
        EXPECT_GT(flip.csf_kernels().radius, previous_radius) << ppd;
        previous_radius = flip.csf_kernels().radius;
        auto terms = flip.terms(checkerboard, gray);
        ASSERT_TRUE(terms) << terms.error().message;
        const double color = interior_mean(terms->color), error = interior_mean(terms->error);
        EXPECT_LT(color, previous_color) << ppd;
        EXPECT_LT(error, previous_error) << ppd;
        previous_color = color;
        previous_error = error;
    }
    EXPECT_LT(previous_color, 0.01); // at 67 pixels per degree, the pattern is all but gray
}

// Both terms take absolute differences: swapping the images changes nothing, to the bit.
TEST(Flip, IsSymmetricInItsTwoImages) {
    const LdrFlip flip(kDefaultPpd);
    const Image a = noise(2), b = noise(3);
    auto ab = flip.terms(a, b), ba = flip.terms(b, a);
    ASSERT_TRUE(ab && ba);
    EXPECT_EQ(ab->color, ba->color);
    EXPECT_EQ(ab->feature, ba->feature);
    EXPECT_EQ(ab->error, ba->error);
    EXPECT_GT(mean_error(ab->error), 0.0);
}

TEST(Flip, RefusesWhatItCannotEvaluateAndSaysWhy) {
    const LdrFlip flip(kDefaultPpd);
    const Image good = flat({0.5f, 0.5f, 0.5f}, 4, 4);
    auto expect_error = [&](const Image& reference, const Image& test, const std::string& message) {
        auto mean = flip.mean(reference, test);
        ASSERT_FALSE(mean) << message;
        EXPECT_NE(mean.error().message.find(message), std::string::npos) << mean.error().message;
        EXPECT_FALSE(flip.error_map(reference, test));
        EXPECT_FALSE(flip.terms(reference, test));
    };
    expect_error(good, flat({0.5f, 0.5f, 0.5f}, 4, 3), "test image: 4x3, but the reference image is 4x4");
    Image bright = good;
    bright.at(2, 1).g = 1.5f;
    expect_error(bright, good, "reference image: pixel (2, 1) has green = 1.5");
    expect_error(bright, good, "HDR-FLIP");
    Image nan = good;
    nan.at(0, 3).r = std::nanf("");
    expect_error(good, nan, "test image: pixel (0, 3) has red = nan");
    Image negative = good;
    negative.at(3, 0).b = -0.25f;
    expect_error(good, negative, "test image: pixel (3, 0) has blue = -0.25");
    expect_error(Image(), Image(), "reference image: the image is empty");
    // Alpha is not looked at.
    Image alpha = good;
    alpha.at(1, 1).a = 7.0f;
    EXPECT_TRUE(flip.mean(alpha, good));

    EXPECT_THROW(LdrFlip(0.5), std::invalid_argument);
    EXPECT_THROW(LdrFlip(std::nan("")), std::invalid_argument);
    EXPECT_THROW(LdrFlip(2000), std::invalid_argument);
    auto ok = check_pixels_per_degree(0);
    ASSERT_FALSE(ok);
    EXPECT_EQ(ok.error().message, "pixels per degree must be a number from 1 to 1000, got 0");
}

// One evaluator, several threads at once: each gets what it gets alone.
TEST(Flip, ThreadsShareOneEvaluator) {
    const LdrFlip flip(kDefaultPpd);
    const Image images[4] = {noise(4), noise(5), noise(6), noise(7)};
    double alone[2], together[2];
    for (int i = 0; i < 2; ++i) alone[i] = *flip.mean(images[2 * i], images[2 * i + 1]);
    std::vector<std::thread> threads;
    for (int i = 0; i < 2; ++i)
        threads.emplace_back([&, i] {
            for (int repeat = 0; repeat < 5; ++repeat) together[i] = *flip.mean(images[2 * i], images[2 * i + 1]);
        });
    for (std::thread& t : threads) t.join();
    EXPECT_EQ(together[0], alone[0]);
    EXPECT_EQ(together[1], alone[1]);
    EXPECT_NE(alone[0], alone[1]);
}

// The per-pixel cube root of L*a*b* against the exact one, over the range L*a*b* takes it
// (above (6/29)^3, up to white and a little beyond for rounding).
TEST(Flip, CubeRootIsTheRootToFloatPrecision) {
    double worst = 0;
    for (float t = 0.0088f; t < 1.01f; t = std::bit_cast<float>(std::bit_cast<std::uint32_t>(t) + 37)) // every 37th
        worst = std::max(worst, std::abs(double(flip::cube_root(t)) - std::cbrt(double(t))) / std::cbrt(double(t)));
    EXPECT_LT(worst, 2.5e-7); // 4 units in the last place
    EXPECT_EQ(flip::cube_root(8.0), 2.0);
}

// matplotlib's magma, indexed as the reference does: int(value * 255 + 0.5).
TEST(Flip, MagmaIndexesTheTableAsTheReferenceDoes) {
    EXPECT_EQ(flip::magma_srgb(0.0f), glm::vec3(0.001462f, 0.000466f, 0.013866f));
    EXPECT_EQ(flip::magma_srgb(0.5f), glm::vec3(0.716387f, 0.214982f, 0.475290f)); // 128
    EXPECT_EQ(flip::magma_srgb(1.0f), glm::vec3(0.987053f, 0.991438f, 0.749504f)); // 255
    EXPECT_EQ(flip::magma_srgb(1.0f / 255 - 0.003f), flip::magma_srgb(0.0f));      // rounds down to 0
    EXPECT_EQ(flip::magma_srgb(2.0f), flip::magma_srgb(1.0f));
    const Image image = flip::magma_image(std::vector<float>{0.5f}, 1, 1);
    EXPECT_NEAR(image.pixels[0].r, flip::srgb_to_linear(0.716387f), 1e-6);
}

} // namespace
} // namespace kdop

namespace kdop {
namespace {

std::string kdop_flip(const std::string& args) { return test::kdop_binary() + " flip " + args; }

// "LDR-FLIP mean <value> at <ppd> pixels per degree (...)": the value, NaN where absent.
double printed_mean(const std::string& out) {
    const std::string prefix = "LDR-FLIP mean ";
    const std::size_t at = out.find(prefix);
    return at == std::string::npos ? NAN : std::stod(out.substr(at + prefix.size()));
}

struct FlipFiles {
    test::TempDir dir;
    Image reference_image = noise(11, 24, 16), test_image = noise(12, 24, 16);
    std::string reference_exr = (dir / "reference.exr").string(), test_exr = (dir / "test.exr").string();
    FlipFiles() {
        for (std::size_t i = 0; i < test_image.pixels.size(); ++i) // a test close to the reference
            test_image.pixels[i] = glm::mix(reference_image.pixels[i], test_image.pixels[i], 0.2f);
        EXPECT_TRUE(write_image(reference_exr, reference_image));
        EXPECT_TRUE(write_image(test_exr, test_image));
    }
    std::string inputs() const { return "--reference " + reference_exr + " --test " + test_exr; }
};

// On the device where one is named (within DeviceFlip's tolerances of the CPU code), on the CPU
// with --cpu (exactly the CPU code's figures), and on the CPU where no device is named: kdop's
// default device, lavapipe, is a CPU, where the CPU code is faster; the output says why.
TEST(CliFlip, PrintsTheMeanAndWritesTheMap) {
    FlipFiles files;
    const LdrFlip flip(kDefaultPpd);
    const std::vector<float> map = *flip.error_map(files.reference_image, files.test_image);
    const double mean = *flip.mean(files.reference_image, files.test_image);
    const std::string exr = (files.dir / "map.exr").string(), png = (files.dir / "map.png").string();

    auto r = test::run(kdop_flip(files.inputs() + " --out " + exr + " --validation"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("at 67.02 pixels per degree (24x16) on llvmpipe"), std::string::npos) << r.out;
    EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
    EXPECT_NEAR(printed_mean(r.out), mean, 1e-6 * mean) << r.out;
    auto written = read_image(exr);
    ASSERT_TRUE(written) << written.error().message;
    ASSERT_EQ(written->pixels.size(), map.size());
    for (std::size_t i = 0; i < map.size(); ++i) ASSERT_NEAR(written->pixels[i].r, map[i], 1e-5) << i;

    r = test::run(kdop_flip(files.inputs() + " --out " + exr + " --cpu"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("at 67.02 pixels per degree (24x16) on the CPU\n"), std::string::npos) << r.out;
    EXPECT_EQ(printed_mean(r.out), mean) << r.out;
    for (const char* environment : {"env -u KDOP_DEVICE ", "env KDOP_DEVICE= "}) {
        auto chosen = test::run(environment + kdop_flip(files.inputs()));
        ASSERT_EQ(chosen.exit_code, 0) << chosen.err;
        EXPECT_NE(chosen.out.find("(24x16) on the CPU (kdop's default device, lavapipe, is a CPU"), std::string::npos)
            << chosen.out;
        EXPECT_EQ(printed_mean(chosen.out), mean) << chosen.out;
    }
    auto named = test::run("env KDOP_DEVICE=llvmpipe " + kdop_flip(files.inputs()));
    ASSERT_EQ(named.exit_code, 0) << named.err;
    EXPECT_NE(named.out.find("(24x16) on llvmpipe"), std::string::npos) << named.out;
    written = read_image(exr);
    ASSERT_TRUE(written) << written.error().message;
    for (std::size_t i = 0; i < map.size(); ++i) ASSERT_EQ(written->pixels[i], glm::vec4(glm::vec3(map[i]), 1)) << i;

    // --timing: the same mean, then the median times of the evaluations after the first.
    for (const char* where : {"", " --cpu"}) {
        auto timed = test::run(kdop_flip(files.inputs() + " --timing 2" + where));
        ASSERT_EQ(timed.exit_code, 0) << timed.err;
        EXPECT_EQ(printed_mean(timed.out), printed_mean(test::run(kdop_flip(files.inputs() + where)).out));
        EXPECT_NE(timed.out.find("timing: median of 2 evaluations: "), std::string::npos) << timed.out;
    }

    r = test::run(kdop_flip(files.inputs() + " --cpu --out " + png));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto colored = read_image(png);
    ASSERT_TRUE(colored) << colored.error().message;
    for (std::size_t i = 0; i < map.size(); ++i) {
        const glm::vec3 expected = flip::magma_image(std::span(&map[i], 1), 1, 1).pixels[0];
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(colored->pixels[i][c], expected[c], 0.5 / 255 + 1e-6) << i;
    }

    // Other viewing conditions, given as pixels per degree or as the display and the distance.
    r = test::run(kdop_flip(files.inputs() + " --ppd 30"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("at 30 pixels per degree"), std::string::npos) << r.out;
    const double at_30 = *LdrFlip(30).mean(files.reference_image, files.test_image);
    EXPECT_NEAR(printed_mean(r.out), at_30, 1e-6 * at_30);
    r = test::run(kdop_flip(files.inputs() + " --cpu --distance 0.5 --display-width 0.6 --display-pixels 2560"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(printed_mean(r.out),
              *LdrFlip(pixels_per_degree({0.5, 0.6, 2560})).mean(files.reference_image, files.test_image));
    EXPECT_NE(printed_mean(r.out), printed_mean(test::run(kdop_flip(files.inputs() + " --cpu")).out));
}

// PNGs hold sRGB-encoded values, and kdop flip decodes them as NVlabs/flip does; --input-space
// linear takes the stored values as they are.
TEST(CliFlip, DecodesSrgbInputsAsTheReferenceDoes) {
    FlipFiles files;
    const std::string reference_png = (files.dir / "reference.png").string(),
                      test_png = (files.dir / "test.png").string();
    ASSERT_TRUE(write_image(reference_png, files.reference_image));
    ASSERT_TRUE(write_image(test_png, files.test_image));
    // The 8-bit values as stored, as NVlabs/flip reads them, then decoded by sRGB's transfer function
    // as its LDR path does.
    Image encoded[2] = {*read_image(reference_png, 0, InputSpace::linear),
                        *read_image(test_png, 0, InputSpace::linear)};
    const LdrFlip flip(kDefaultPpd);
    const std::string inputs = "--cpu --reference " + reference_png + " --test " + test_png;

    auto r = test::run(kdop_flip(inputs + " --input-space linear"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("every input taken as linear"), std::string::npos) << r.out;
    EXPECT_EQ(printed_mean(r.out), *flip.mean(encoded[0], encoded[1]));
    for (Image& image : encoded)
        for (glm::vec4& p : image.pixels)
            p = glm::vec4(flip::srgb_to_linear(p.r), flip::srgb_to_linear(p.g), flip::srgb_to_linear(p.b), p.a);
    const double decoded = *flip.mean(encoded[0], encoded[1]);
    r = test::run(kdop_flip(inputs));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(printed_mean(r.out), decoded) << "decoded by default, as the file says";
    r = test::run(kdop_flip(inputs + " --srgb"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("every input decoded from sRGB"), std::string::npos) << r.out;
    EXPECT_EQ(printed_mean(r.out), decoded);
    // Close to the EXR pair's, which holds the same linear values unquantized.
    EXPECT_NEAR(decoded, *flip.mean(files.reference_image, files.test_image), 0.01);
}

// flip_statistics on a map whose distribution is known: the plain percentiles as numpy.quantile
// computes them (linear), the weighted ones as NVlabs/flip's tool prints them, written out here
// another way: the running sums in an array, the first that passes found by search.
TEST(FlipStatistics, PercentilesOfAKnownMap) {
    std::vector<float> map;
    for (int i = 0; i < 1000; ++i) map.push_back(float(i % 97) * float(i % 13) / (96.0f * 12.0f)); // in [0, 1]
    map.push_back(1.0f);
    const FlipStatistics f = flip_statistics(map);

    std::vector<double> sorted(map.begin(), map.end());
    std::sort(sorted.begin(), sorted.end());
    auto numpy_quantile = [&](double q) {
        const double h = (double(sorted.size()) - 1) * q;
        const double lower = sorted[std::size_t(std::floor(h))], upper = sorted[std::size_t(std::ceil(h))];
        return lower + (h - std::floor(h)) * (upper - lower);
    };
    EXPECT_EQ(f.mean, mean_error(map));
    EXPECT_DOUBLE_EQ(f.median, numpy_quantile(0.5));
    EXPECT_DOUBLE_EQ(f.q1, numpy_quantile(0.25));
    EXPECT_DOUBLE_EQ(f.q3, numpy_quantile(0.75));
    EXPECT_EQ(f.min, 0.0);
    EXPECT_EQ(f.max, 1.0);

    // The histogram the weighted plot draws: 100 buckets of width 0.01, 1.0 in the last.
    const std::vector<std::size_t> histogram = flip_histogram(map);
    ASSERT_EQ(histogram.size(), 100u);
    EXPECT_EQ(std::accumulate(histogram.begin(), histogram.end(), std::size_t(0)), map.size());
    EXPECT_EQ(histogram[99], std::size_t(std::count_if(map.begin(), map.end(), [](float v) { return v >= 0.99f; })));
    // The weighted percentiles NVlabs/flip's tool prints: the running float sums of the sorted
    // values, and the first value whose sum passes p times the float total of the map.
    std::vector<float> ascending(map);
    std::sort(ascending.begin(), ascending.end());
    std::vector<float> running(ascending.size());
    std::partial_sum(ascending.begin(), ascending.end(), running.begin());
    const float total = std::accumulate(map.begin(), map.end(), 0.0f);
    auto weighted = [&](float p) {
        return double(
            ascending[std::size_t(std::upper_bound(running.begin(), running.end(), p * total) - running.begin())]);
    };
    EXPECT_EQ(f.weighted_median, weighted(0.5f));
    EXPECT_EQ(f.weighted_q1, weighted(0.25f));
    EXPECT_EQ(f.weighted_q3, weighted(0.75f));
    // Weighting by the error moves the percentiles up: a pixel's vote grows with its error.
    EXPECT_GT(f.weighted_median, f.median);

    // Values apart only in their last bits, shuffled: ordered by them too.
    std::vector<float> close(257);
    for (std::size_t i = 0; i < close.size(); ++i)
        close[i] = std::nextafter(0.5f, 1.0f) + float((i * 97) % 257) * 1e-7f;
    const FlipStatistics c = flip_statistics(close);
    std::sort(close.begin(), close.end());
    EXPECT_EQ(c.median, close[128]);
    EXPECT_EQ(c.q1, close[64]);
    EXPECT_EQ(c.min, close.front());
    EXPECT_EQ(c.max, close.back());

    // A map of zeros: no sum to pass, and the tool's 0.
    const std::vector<float> zeros(64, 0.0f);
    EXPECT_EQ(flip_statistics(zeros).weighted_median, 0.0);
    EXPECT_EQ(flip_statistics(zeros).median, 0.0);
}

// Several test images against one reference, on one device: each block what a call of its own
// prints, a CSV with the same figures, and a histogram picture.
TEST(CliFlip, SeveralTestsInOneCallGiveWhatSeparateCallsGive) {
    FlipFiles files;
    const std::string second = (files.dir / "second.exr").string();
    Image other = files.test_image;
    for (glm::vec4& p : other.pixels) p = glm::vec4(glm::vec3(p) * 0.8f, 1.0f);
    ASSERT_TRUE(write_image(second, other));
    const std::string csv = (files.dir / "figures.csv").string(), chart = (files.dir / "histogram.png").string();
    auto together = test::run(kdop_flip("--reference " + files.reference_exr + " --test " + files.test_exr + " " +
                                        second + " --csv " + csv + " --histogram " + chart));
    ASSERT_EQ(together.exit_code, 0) << together.err;
    const auto rows = test::csv_rows(test::read_file(csv));
    ASSERT_EQ(rows.size(), 2u);
    for (std::size_t t = 0; t < 2; ++t) {
        const std::string test = t == 0 ? files.test_exr : second;
        auto alone = test::run(kdop_flip("--reference " + files.reference_exr + " --test " + test));
        ASSERT_EQ(alone.exit_code, 0) << alone.err;
        // The block after "<test>: " is the single call's output.
        const std::size_t at = together.out.find(test + ": LDR-FLIP mean ");
        ASSERT_NE(at, std::string::npos) << together.out;
        const std::size_t end = together.out.find("\n", together.out.find("max ", at));
        EXPECT_EQ(together.out.substr(at + test.size() + 2, end + 1 - at - test.size() - 2), alone.out);
        auto row = rows[t];
        EXPECT_EQ(row["test"], test);
        EXPECT_DOUBLE_EQ(std::stod(row["mean"]), printed_mean(alone.out));
        const std::string weighted = "weighted median ";
        EXPECT_NEAR(std::stod(row["weighted_median"]),
                    std::stod(alone.out.substr(alone.out.find(weighted) + weighted.size())), 5e-7);
        for (const char* column : {"weighted_q1", "weighted_q3", "median", "q1", "q3", "min", "max"})
            EXPECT_FALSE(row[column].empty()) << column;
        EXPECT_LE(std::stod(row["min"]), std::stod(row["q1"]));
        EXPECT_LE(std::stod(row["q3"]), std::stod(row["max"]));
    }
    auto picture = read_image(chart);
    ASSERT_TRUE(picture) << picture.error().message;
    EXPECT_EQ(picture->width, 1000u);

    // --out and --exposure-map are one test's.
    const std::string map = (files.dir / "map.exr").string();
    auto refused = test::run(
        kdop_flip("--reference " + files.reference_exr + " --test " + files.test_exr + " " + second + " --out " + map));
    EXPECT_EQ(refused.exit_code, 2);
    EXPECT_NE(refused.err.find("--out and --exposure-map write one test's maps"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(map));
    auto same = test::run(kdop_flip(files.inputs() + " --csv " + csv + " --histogram " + csv));
    EXPECT_EQ(same.exit_code, 2) << same.err;
}

TEST(CliFlip, RefusesBadInputAndWritesNothing) {
    FlipFiles files;
    const std::string small = (files.dir / "small.exr").string(), bright = (files.dir / "bright.exr").string(),
                      nan = (files.dir / "nan.exr").string(), out = (files.dir / "map.exr").string();
    ASSERT_TRUE(write_image(small, noise(13, 8, 8)));
    Image image = files.reference_image;
    image.at(5, 3).b = 2.5f;
    ASSERT_TRUE(write_image(bright, image));
    image = files.reference_image;
    image.at(0, 1).g = std::nanf("");
    ASSERT_TRUE(write_image(nan, image));
    const std::string reference = "--reference " + files.reference_exr;
    struct Case {
        std::string args;
        int exit_code;
        std::string message;
    };
    const Case cases[] = {
        {reference + " --test " + small, 1,
         fmt::format("--test {}: 8x8, but --reference {} is 24x16", small, files.reference_exr)},
        {reference + " --test " + bright, 1,
         fmt::format("--test {}: pixel (5, 3) has blue = 2.5; LDR-FLIP takes linear RGB from 0 to 1", bright)},
        {reference + " --test " + bright, 1, "for other values, HDR-FLIP: kdop flip --hdr"},
        {"--reference " + nan + " --test " + files.test_exr, 1,
         fmt::format("--reference {}: pixel (0, 1) has green = nan", nan)},
        {reference + " --test " + (files.dir / "missing.exr").string(), 1, "missing.exr"},
        {files.inputs() + " --ppd 0", 2, "--ppd"},
        {files.inputs() + " --ppd nan", 2, "--ppd: 'nan' is not a number from 1 to 1000"},
        {files.inputs() + " --ppd 30 --distance 1", 2, "--ppd excludes --distance"},
        {files.inputs() + " --distance 0", 2, "--distance"},
        {files.inputs() + " --display-pixels 10", 2,
         "--distance 0.7 --display-width 0.7 --display-pixels 10: pixels per degree must be a number from 1 to 1000"},
        {files.inputs() + " --cpu --device llvmpipe", 2, "--cpu excludes --device"},
        {files.inputs() + " --timing 0", 2, "--timing"},
        {files.inputs() + " --device no-such-device", 1, "no-such-device"},
    };
    for (const Case& c : cases) {
        auto r = test::run(kdop_flip(c.args + " --out " + out));
        EXPECT_EQ(r.exit_code, c.exit_code) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\nstderr was: " << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
        EXPECT_FALSE(fs::exists(out)) << c.args;
    }
    auto r = test::run(kdop_flip(files.inputs() + " --out " + (files.dir / "map.jpg").string()));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("the map is written as .exr (its values) or .png (in magma colors)"), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(files.dir / "map.jpg"));
    r = test::run(kdop_flip(files.inputs() + " --out /proc/kdop-flip/map.exr"));
    EXPECT_EQ(r.exit_code, 2) << "a --out that cannot be written is a wrong command line";
    EXPECT_NE(r.err.find("--out: /proc/kdop-flip"), std::string::npos) << r.err;
}

} // namespace
} // namespace kdop
