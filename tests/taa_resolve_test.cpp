// The TAA resolve of examples/taa_resolve, built into this test binary the way a renderer builds it
// (kdop_add_variants SHADERS, tests/CMakeLists.txt), run on lavapipe with the validation layer on
// and checked against the CPU reference: the history moved by the motion (clamp to edge), clipped
// by the reference dop22 clip, then blended with the current frame.
#include "images/texture_cases.h"
#include "kdop_test_shaders.h"
#include "reference/cpu_clip.h"
#include "tests/gpu_support.h"

#include <gtest/gtest.h>

#include <glm/common.hpp>

namespace kdop {
namespace {

constexpr std::uint32_t kSize = 48;
// Content and tolerance of gpu_reference_test.cpp, whose derivation holds for this content: 2e-4 of
// the pixel's magnitude. (Content with a ray nearly parallel to a slab through the current color
// can exceed it, for the standalone variant alike: float32 cancels in the ray's projection there.)
constexpr std::uint64_t kSeed = 7;
constexpr double kTolerance = 2e-4;

TEST(TaaResolve, ReprojectsClipsAndBlendsAsTheReferenceDoes) {
    const Variant* resolve = test_shaders::variants().find("taa_resolve");
    ASSERT_NE(resolve, nullptr);
    EXPECT_EQ(resolve->mode, Mode::shader);
    const std::size_t validation_before = test::gpu().validation_messages().size();

    auto kernel = Kernel::create(test::gpu(), *resolve);
    ASSERT_TRUE(kernel) << kernel.error().message;
    auto pass = RectifyPass::create(test::gpu(), kSize, kSize, TextureFormat::rgba32f);
    ASSERT_TRUE(pass) << pass.error().message;
    auto dop22 = resolve_axis_set("dop22");
    ASSERT_TRUE(dop22);

    const glm::ivec2 motion(3, -2);
    const float weight = 0.1f;
    std::size_t checked = 0;
    for (const TestCase& c : make_test_cases(kSize, kSize, kSeed)) {
        ASSERT_TRUE((*pass)->upload(c.current, c.history));
        const RectifyPass::PushConstantValue push[] = {{"motion", {float(motion.x), float(motion.y)}},
                                                       {"current_weight", {weight}}};
        ASSERT_TRUE((*pass)->dispatch(**kernel, push));
        auto gpu = (*pass)->download();
        ASSERT_TRUE(gpu);

        Image reprojected(kSize, kSize);
        for (std::uint32_t y = 0; y < kSize; ++y)
            for (std::uint32_t x = 0; x < kSize; ++x)
                reprojected.at(x, y) = c.history.clamped(int(x) - motion.x, int(y) - motion.y);
        Image expected = reference_rectify(*dop22, Mode::clip, Neighborhood::n9, c.current, reprojected, 1.0);
        for (std::size_t i = 0; i < expected.pixels.size(); ++i)
            expected.pixels[i] = glm::mix(expected.pixels[i], glm::vec4(glm::vec3(c.current.pixels[i]), 1), weight);

        auto e = test::relative_error(*gpu, expected, c.current, reprojected);
        EXPECT_LE(e.max_relative, kTolerance) << c.name() << " at " << e.x << "," << e.y;

        // Its clip is the embedded variant's: the standalone pass on the reprojected history,
        // blended on the CPU, agrees up to the blend's rounding.
        Image standalone = test::run_on_gpu(test::builtin_variant("dop22-clip-n9"), c.current, reprojected);
        for (std::size_t i = 0; i < standalone.pixels.size(); ++i)
            standalone.pixels[i] = glm::mix(standalone.pixels[i], glm::vec4(glm::vec3(c.current.pixels[i]), 1), weight);
        auto s = test::relative_error(*gpu, standalone, c.current, reprojected);
        EXPECT_LE(s.max_relative, 1e-6) << c.name() << " at " << s.x << "," << s.y;
        ++checked;
    }
    EXPECT_GE(checked, 24u);

    const RectifyPass::PushConstantValue missing[] = {{"motion", {0, 0}}};
    auto refused = (*pass)->dispatch(**kernel, missing);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("current_weight"), std::string::npos) << refused.error().message;

    auto messages = test::gpu().validation_messages();
    for (std::size_t i = validation_before; i < messages.size(); ++i) ADD_FAILURE() << "validation: " << messages[i];
}

} // namespace
} // namespace kdop
