// The HLSL function of every default variant, compiled through glslang's HLSL front end inside
// shader_templates/rectify.hlsl.in and run on lavapipe with the Khronos validation layer on, on the
// inputs gpu_reference_test.cpp uses.
//
// What is checked: within the GLSL test's tolerance (2e-4 of the pixel's color magnitude, reasoned
// there) of the CPU reference, and bit for bit equal to the GLSL variant's output on every pixel.
// The second is the stronger claim and holds because the HLSL function performs the same operations
// in the same order (hlsl_emitter_test.cpp) and compiles to the same float arithmetic
// (hlsl_build_test.cpp); a difference would mean the two languages' functions have drifted apart.
#include "generator/runnable_variant.h"
#include "generator/variant_builder.h"
#include "images/texture_cases.h"
#include "reference/cpu_clip.h"
#include "tests/gpu_support.h"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>

namespace kdop {
namespace {

constexpr double kTolerance = 2e-4; // as gpu_reference_test.cpp
constexpr std::uint32_t kSize = 48;
constexpr std::uint64_t kSeed = 7;
constexpr float kGamma = 1.0f;

class GpuHlsl : public test::ValidationChecked {};

// Pixels whose RGB differ in any bit (NaN payloads included).
std::size_t differing_pixels(const Image& a, const Image& b) {
    std::size_t count = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        if (std::memcmp(&a.pixels[i], &b.pixels[i], 3 * sizeof(float)) != 0) ++count;
    return count;
}

TEST_F(GpuHlsl, EveryDefaultVariantMatchesTheReferenceAndItsGlslBitForBit) {
    const auto cases = make_test_cases(kSize, kSize, kSeed);
    ASSERT_GE(cases.size(), 24u);
    auto specs = select_variants({}, {}, {});
    ASSERT_TRUE(specs);
    ASSERT_EQ(specs->size(), 24u) << "every set, clip and varclip, n9 and n5";
    double worst_reference = 0;
    for (const VariantSpec& spec : *specs) {
        const std::string name = variant_name(spec);
        SCOPED_TRACE(name);
        auto built = build_variant(spec, SourceLanguage::hlsl);
        ASSERT_TRUE(built) << built.error().message;
        const RunnableVariant hlsl(std::move(*built));
        const Variant& glsl = test::builtin_variant(name);
        ASSERT_NE(hlsl.variant().spirv_hash, glsl.spirv_hash) << "the HLSL build must be a module of its own";
        const Variant* both[] = {&hlsl.variant(), &glsl};
        for (const TestCase& c : cases) {
            Image outputs[2];
            auto ran = test::runner().run(c.current, c.history, TextureFormat::rgba32f, both, kGamma,
                                          [&](std::size_t i, const Image& out) -> Result<void> {
                                              outputs[i] = out;
                                              return {};
                                          });
            ASSERT_TRUE(ran) << ran.error().message;
            Image ref = reference_rectify(spec.set, spec.mode, spec.neighborhood, c.current, c.history, kGamma);
            auto e = test::relative_error(outputs[0], ref, c.current, c.history);
            EXPECT_LE(e.max_relative, kTolerance) << c.name() << " at " << e.x << "," << e.y;
            worst_reference = std::max(worst_reference, e.max_relative);
            EXPECT_EQ(differing_pixels(outputs[0], outputs[1]), 0u) << c.name() << ": HLSL and GLSL outputs differ";
        }
    }
    RecordProperty("worst_relative_error_against_reference", std::to_string(worst_reference));
}

// The bit-for-bit comparison has teeth: the same clip in the loop form (axes at unit length rather
// than scaled, the same function to within the reference tolerance) rounds differently, and the
// comparison sees it. (A different EmitStyle does not: on lavapipe, which splits every Fma, dot
// products and multiply-adds, min/max trees and chains give the same bits.)
TEST_F(GpuHlsl, TheComparisonSeesADifferentlyWrittenFunction) {
    VariantSpec spec = test::builtin_spec(test::builtin_variant("dop32-clip-n9"));
    spec.form = Form::loop;
    auto built = build_variant(spec, SourceLanguage::hlsl);
    ASSERT_TRUE(built) << built.error().message;
    const RunnableVariant hlsl(std::move(*built));
    std::size_t differing = 0;
    for (const TestCase& c : make_test_cases(kSize, kSize, kSeed))
        differing += differing_pixels(test::run_on_gpu(hlsl.variant(), c.current, c.history),
                                      test::run_on_gpu(test::builtin_variant("dop32-clip-n9"), c.current, c.history));
    EXPECT_GT(differing, 0u);
}

} // namespace
} // namespace kdop
