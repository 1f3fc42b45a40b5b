// Every emission style computes the same function: built in-process, run on lavapipe, compared
// with the CPU reference (same tolerance and reasoning as gpu_reference_test.cpp).
#include "generator/clip_emitter.h"
#include "generator/runnable_variant.h"
#include "generator/variant_builder.h"
#include "images/texture_cases.h"
#include "reference/cpu_clip.h"
#include "tests/gpu_support.h"

#include <gtest/gtest.h>

namespace kdop {
namespace {

constexpr double kTolerance = 2e-4;

TEST(EmitStyle, EveryStyleMatchesTheReference) {
    const auto cases = make_test_cases(32, 32, 11, false);
    for (auto projection :
         {EmitStyle::Projection::fold_dot, EmitStyle::Projection::multiply_add, EmitStyle::Projection::full_dot})
        for (auto extent : {EmitStyle::Extent::tree, EmitStyle::Extent::running})
            for (const char* name : {"dop22-clip-n9", "dop22-varclip-n5"}) {
                const Variant& registered = test::builtin_variant(name);
                VariantSpec spec = test::builtin_spec(registered);
                spec.style = {projection, extent};
                auto built = build_variant(spec);
                ASSERT_TRUE(built) << built.error().message;
                // The runner keeps pipelines by name and module, so this style's module gets its own.
                const RunnableVariant runnable(std::move(*built));
                const Variant& variant = runnable.variant();
                SCOPED_TRACE(std::string(name) + " projection " + std::to_string(int(projection)) + " extent " +
                             std::to_string(int(extent)));
                for (const TestCase& c : cases) {
                    Image gpu = test::run_on_gpu(variant, c.current, c.history);
                    Image ref = reference_rectify(spec.set, spec.mode, spec.neighborhood, c.current, c.history, 1.0);
                    EXPECT_LE(test::relative_error(gpu, ref, c.current, c.history).max_relative, kTolerance)
                        << c.name();
                }
            }
}

TEST(EmitStyle, ProjectionsAreWrittenAsAsked) {
    VariantSpec spec = test::builtin_spec(test::builtin_variant("dop32-clip-n9"));
    spec.style.projection = EmitStyle::Projection::multiply_add;
    std::string ma = emit_function(spec);
    EXPECT_EQ(ma.find("dot("), std::string::npos);
    EXPECT_NE(ma.find("float q0 = c0.x + c0.y * "), std::string::npos);
    spec.style.projection = EmitStyle::Projection::full_dot;
    std::string fd = emit_function(spec);
    EXPECT_NE(fd.find("float q0 = dot(c0, vec3(1.0, 0.5569"),
              std::string::npos);                              // axis 4: (0.820081, 0.456727, -0.344773)
    EXPECT_NE(fd.find("float q0 = c0.x;"), std::string::npos); // axis 1: X
    spec.style.extent = EmitStyle::Extent::running;
    std::string running = emit_function(spec);
    EXPECT_NE(running.find("float lo = 0.0;"), std::string::npos); // from current, the origin
    EXPECT_NE(running.find("lo = min(lo, q8);"), std::string::npos);
}

} // namespace
} // namespace kdop
