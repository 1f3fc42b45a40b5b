// The runtime checked against the CPU reference: every default variant on every test texture and
// ghosting history, on lavapipe with the Khronos validation layer on; and the geometric
// invariants of a clip, checked on the GPU's output.
//
// Tolerance: 2e-4 of the pixel's color magnitude max(1, |current|, |history|). Why: float32 rounds
// each operation by up to 6e-8 relative; a slab's exit bound (projections, min/max, subtraction)
// carries about ten of those, times |color|, and the exit parameter divides it by the ray's
// projection on the limiting slab, which on this content is no smaller than about 1/300 of |dir|:
// 10 x 6e-8 x 300 = 2e-4. Measured worst case over all variants and textures: 2.6e-5.
#include "images/texture_cases.h"
#include "reference/cpu_clip.h"
#include "tests/gpu_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

namespace kdop {
namespace {

constexpr double kTolerance = 2e-4;
constexpr std::uint32_t kSize = 48; // every texture family repeats its structure within this
constexpr std::uint64_t kSeed = 7;
constexpr float kGamma = 1.0f;

const std::vector<TestCase>& cases() {
    static const auto all = make_test_cases(kSize, kSize, kSeed);
    return all;
}

std::vector<std::string> default_variant_names() {
    std::vector<std::string> names;
    auto specs = select_variants({}, {}, {});
    for (const VariantSpec& s : *specs) names.push_back(variant_name(s));
    return names;
}

double magnitude(const glm::vec4& a, const glm::vec4& b) {
    glm::vec3 m = glm::max(glm::abs(glm::vec3(a)), glm::abs(glm::vec3(b)));
    return std::max({1.0f, m.x, m.y, m.z});
}

class Gpu : public test::ValidationChecked {};

TEST_F(Gpu, EveryDefaultVariantMatchesTheReferenceAndItsLoopForm) {
    ASSERT_GE(cases().size(), 24u) << "six synthetic families x four history models at least";
    for (const std::string& name : default_variant_names()) {
        const Variant& v = test::builtin_variant(name);
        const Variant& loop = test::builtin_variant(name + "-loop");
        VariantSpec spec = test::builtin_spec(v);
        for (const TestCase& c : cases()) {
            Image gpu = test::run_on_gpu(v, c.current, c.history, TextureFormat::rgba32f, kGamma);
            Image ref = reference_rectify(spec.set, spec.mode, spec.neighborhood, c.current, c.history, kGamma);
            auto e = test::relative_error(gpu, ref, c.current, c.history);
            EXPECT_LE(e.max_relative, kTolerance) << name << " on " << c.name() << " at " << e.x << "," << e.y;
            auto el = test::relative_error(test::run_on_gpu(loop, c.current, c.history, TextureFormat::rgba32f, kGamma),
                                           gpu, c.current, c.history);
            EXPECT_LE(el.max_relative, kTolerance) << name << "-loop on " << c.name() << " at " << el.x << "," << el.y;
        }
    }
}

TEST_F(Gpu, Rgba16fInputsMatchTheReferenceOnHalfRoundedInputs) {
    auto to_half = [](Image image) {
        for (glm::vec4& p : image.pixels) p = glm::unpackHalf4x16(glm::packHalf4x16(p));
        return image;
    };
    for (std::string name : {"aabb-clip-n9", "dop16-grass-varclip-n5", "dop32-clip-n9", "dop22-varclip-n9"}) {
        const Variant& v = test::builtin_variant(name);
        VariantSpec spec = test::builtin_spec(v);
        for (const TestCase& c : cases()) {
            Image current = to_half(c.current), history = to_half(c.history);
            Image gpu = test::run_on_gpu(v, c.current, c.history, TextureFormat::rgba16f, kGamma);
            Image ref = reference_rectify(spec.set, spec.mode, spec.neighborhood, current, history, kGamma);
            auto e = test::relative_error(gpu, ref, current, history);
            EXPECT_LE(e.max_relative, kTolerance)
                << name << " (rgba16f) on " << c.name() << " at " << e.x << "," << e.y;
        }
    }
}

TEST_F(Gpu, HistoryInsideTheKdopComesBackUnchanged) {
    // Two histories inside every variant's k-DOP: the current color itself, and the mean of the
    // neighborhood (a convex combination of its colors, and on every axis exactly the variance
    // slab's center).
    for (const std::string& name : default_variant_names()) {
        const Variant& v = test::builtin_variant(name);
        for (const TestCase& c : cases()) {
            if (c.model != HistoryModel::same) continue;
            Image mean(c.current.width, c.current.height);
            auto offsets = reference_offsets(v.neighborhood);
            for (std::uint32_t y = 0; y < kSize; ++y)
                for (std::uint32_t x = 0; x < kSize; ++x) {
                    glm::dvec3 sum(0);
                    for (glm::ivec2 o : offsets) sum += glm::dvec3(c.current.clamped(int(x) + o.x, int(y) + o.y));
                    mean.at(x, y) = glm::vec4(glm::vec3(sum / double(offsets.size())), 1);
                }
            Image same = test::run_on_gpu(v, c.current, c.current, TextureFormat::rgba32f, kGamma);
            EXPECT_EQ(test::relative_error(same, c.current, c.current, c.current).max_relative, 0.0)
                << name << " " << c.texture;
            Image inside = test::run_on_gpu(v, c.current, mean, TextureFormat::rgba32f, kGamma);
            auto e = test::relative_error(inside, mean, c.current, mean);
            EXPECT_LE(e.max_relative, kTolerance) << name << " on " << c.texture << " at " << e.x << "," << e.y;
        }
    }
}

TEST_F(Gpu, OutputLiesOnTheSegmentFromCurrentToHistory) {
    for (const std::string& name : default_variant_names()) {
        const Variant& v = test::builtin_variant(name);
        for (const TestCase& c : cases()) {
            Image out = test::run_on_gpu(v, c.current, c.history, TextureFormat::rgba32f, kGamma);
            double worst = 0;
            for (std::size_t i = 0; i < out.pixels.size(); ++i) {
                glm::dvec3 cur(c.current.pixels[i]), dir = glm::dvec3(c.history.pixels[i]) - cur, o(out.pixels[i]);
                double len2 = glm::dot(dir, dir);
                double s = len2 > 0 ? std::clamp(glm::dot(o - cur, dir) / len2, 0.0, 1.0) : 0.0;
                worst = std::max(worst, glm::length(o - (cur + s * dir)) /
                                            magnitude(c.current.pixels[i], c.history.pixels[i]));
            }
            EXPECT_LE(worst, kTolerance) << name << " on " << c.name();
        }
    }
}

TEST_F(Gpu, ClipsWithXyzAxesStayInTheNeighborhoodsChannelRange) {
    // aabb, dop22 and dop32 contain the X, Y and Z axes, so their k-DOP lies inside the padded
    // per-channel box of the neighborhood. (Variance clips are exempt: mean - sigma can fall below
    // the minimum, e.g. eight zeros and a one.)
    for (std::string name :
         {"aabb-clip-n9", "aabb-clip-n5", "dop22-clip-n9", "dop22-clip-n5", "dop32-clip-n9", "dop32-clip-n5"}) {
        const Variant& v = test::builtin_variant(name);
        auto offsets = reference_offsets(v.neighborhood);
        for (const TestCase& c : cases()) {
            Image out = test::run_on_gpu(v, c.current, c.history);
            for (std::uint32_t y = 0; y < kSize; ++y)
                for (std::uint32_t x = 0; x < kSize; ++x) {
                    glm::vec3 lo(INFINITY), hi(-INFINITY);
                    for (glm::ivec2 o : offsets) {
                        glm::vec3 n(c.current.clamped(int(x) + o.x, int(y) + o.y));
                        lo = glm::min(lo, n);
                        hi = glm::max(hi, n);
                    }
                    const double slack =
                        kReferencePadding + kTolerance * magnitude(c.current.at(x, y), c.history.at(x, y));
                    for (int ch = 0; ch < 3; ++ch) {
                        ASSERT_GE(out.at(x, y)[ch], lo[ch] - slack)
                            << name << " on " << c.name() << " at " << x << "," << y;
                        ASSERT_LE(out.at(x, y)[ch], hi[ch] + slack)
                            << name << " on " << c.name() << " at " << x << "," << y;
                    }
                }
        }
    }
}

// A size past the device's limit is refused by kdop, naming the limit, before Vulkan sees it (the
// fixture fails the test on any validation message).
TEST_F(Gpu, ImagesLargerThanTheDeviceAllowsAreRefused) {
    const uint32_t limit = test::gpu().properties().limits.maxImageDimension2D;
    auto pass = RectifyPass::create(test::gpu(), limit + 1, 1, TextureFormat::rgba32f);
    ASSERT_FALSE(pass);
    EXPECT_NE(pass.error().message.find(fmt::format("at most {} pixels on a side", limit)), std::string::npos)
        << pass.error().message;
}

TEST_F(Gpu, BaselineKernelsDoWhatTheySay) {
    const TestCase& c = cases().front();
    Image copy = test::run_on_gpu(test::builtin_variant("copy"), c.current, c.history);
    EXPECT_EQ(test::relative_error(copy, c.history, c.current, c.history).max_relative, 0.0);
    Image gather = test::run_on_gpu(test::builtin_variant("gather-n5"), c.current, c.history);
    glm::dvec3 expected(c.history.at(10, 10));
    for (glm::ivec2 o : reference_offsets(Neighborhood::n5)) expected += glm::dvec3(c.current.at(10 + o.x, 10 + o.y));
    EXPECT_NEAR(gather.at(10, 10).g, expected.g, 1e-5 * std::abs(expected.g) + 1e-6);
}

TEST(GpuValidation, TheLayerReportsMisuse) {
    // The tests above trust an empty message list; this shows the list fills when the API is misused.
    auto context = Context::create({"", true});
    ASSERT_TRUE(context) << context.error().message;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = 0; // invalid: VUID-VkBufferCreateInfo-size-00912
    info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    vkCreateBuffer((*context)->device(), &info, nullptr, &buffer);
    if (buffer) vkDestroyBuffer((*context)->device(), buffer, nullptr);
    auto messages = (*context)->validation_messages();
    ASSERT_FALSE(messages.empty());
    EXPECT_NE(messages.front().find("size"), std::string::npos) << messages.front();
}

// HDR accuracy against the exact clip: a clip whose padding grew with the pixel's
// brightest channel loosened the slabs of its dim channels, and on highlights left the exact clip
// by up to 0.51 S on 0.10-0.19% of interior pixels. Every default clip variant must stay within
// 1e-3 S of the exact clip (double precision, the paper's 1e-5 padding of the whole slab; S =
// max(1, |current|)) on at least 99.95% of interior pixels, and within 0.05 S on all of them, on
// grass with 3% highlights from 1e2 to 5e4 under a history panned by (9, 5) pixels.
TEST_F(Gpu, HdrHighlightsStayCloseToTheExactClip) {
    constexpr std::uint32_t size = 128;
    const Image current = make_texture(TextureFamily::highlights, size, size, kSeed);
    Image history(size, size);
    for (std::uint32_t y = 0; y < size; ++y)
        for (std::uint32_t x = 0; x < size; ++x) history.at(x, y) = current.clamped(int(x) - 9, int(y) - 5);
    for (const std::string& name : default_variant_names()) {
        const Variant& v = test::builtin_variant(name);
        if (v.mode != Mode::clip) continue;
        const VariantSpec spec = test::builtin_spec(v);
        const Image out = test::run_on_gpu(v, current, history);
        const Image exact =
            reference_rectify(spec.set, spec.mode, spec.neighborhood, current, history, 1.0, Numerics::paper);
        std::size_t interior = 0, beyond = 0;
        double worst = 0;
        for (std::uint32_t y = 1; y + 1 < size; ++y)
            for (std::uint32_t x = 1; x + 1 < size; ++x) {
                const glm::vec3 c(current.at(x, y));
                const double s = std::max({1.0f, std::abs(c.r), std::abs(c.g), std::abs(c.b)});
                const double off =
                    glm::distance(glm::dvec3(glm::vec3(out.at(x, y))), glm::dvec3(glm::vec3(exact.at(x, y)))) / s;
                ++interior;
                beyond += off > 1e-3;
                worst = std::max(worst, off);
            }
        const double fraction = double(beyond) / double(interior);
        std::printf("%-24s beyond 1e-3 S: %.4f%% of %zu interior pixels; farthest %.2e S\n", name.c_str(),
                    100 * fraction, interior, worst);
        EXPECT_LE(fraction, 0.0005) << name;
        EXPECT_LE(worst, 0.05) << name;
    }
}

} // namespace
} // namespace kdop
