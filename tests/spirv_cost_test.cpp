// The static float-op count, on shaders small enough to count by hand. The inputs come from a
// buffer so that nothing folds to a constant; glslang's output is used unoptimized.
#include "generator/glsl_compiler.h"
#include "generator/spirv_cost.h"

#include <gtest/gtest.h>

namespace kdop {
namespace {

FloatOps count(const std::string& body) {
    const std::string source =
        "#version 450\nlayout(local_size_x = 1) in;\n"
        "layout(set = 0, binding = 0) buffer B { vec3 a; vec3 b; vec3 c; float s; vec3 r; } io;\n"
        "void main()\n{\n    vec3 a = io.a, b = io.b, c = io.c; float s = io.s;\n" +
        body + "\n}\n";
    auto words = compile_glsl_compute(source, "cost.comp");
    EXPECT_TRUE(words) << words.error().message;
    return words ? count_float_ops(*words) : FloatOps{};
}

TEST(FloatOps, CountsVectorOperationsPerComponent) {
    FloatOps ops = count("io.r = a * b + c - a;"); // vec3: 3 mul, 6 add/sub
    EXPECT_EQ(ops.mul, 3u);
    EXPECT_EQ(ops.add_sub, 6u);
    EXPECT_EQ(ops.total(), 9u);
    EXPECT_EQ(count("io.r = a * s;").mul, 3u);  // OpVectorTimesScalar
    EXPECT_EQ(count("io.r = -a;").add_sub, 3u); // OpFNegate
    EXPECT_EQ(count("io.r = a / b;").div, 3u);
}

TEST(FloatOps, CountsDotAs2NMinus1AndFmaAsOne) {
    FloatOps dot3 = count("io.r.x = dot(a, b);");
    EXPECT_EQ(dot3.mul, 3u);
    EXPECT_EQ(dot3.add_sub, 2u);
    EXPECT_EQ(count("io.r.x = dot(a.xy, b.yz);").total(), 3u);
    FloatOps fma3 = count("io.r = fma(a, b, c);");
    EXPECT_EQ(fma3.fma, 3u);
    EXPECT_EQ(fma3.total(), 3u);
}

TEST(FloatOps, CountsMinMaxClampCompareSelectAndOther) {
    EXPECT_EQ(count("io.r = min(a, b);").min_max, 3u);
    EXPECT_EQ(count("io.r.xy = max(a.xy, b.xy);").min_max, 2u);
    EXPECT_EQ(count("io.r = clamp(a, b, c);").min_max, 6u);
    EXPECT_EQ(count("io.r = mix(a, b, lessThan(a, c));").compare_select, 6u); // 3 compares, 3 selects
    EXPECT_EQ(count("io.r.x = sqrt(s);").other, 1u);
    EXPECT_EQ(count("io.r = a;").total(), 0u);
}

} // namespace
} // namespace kdop
