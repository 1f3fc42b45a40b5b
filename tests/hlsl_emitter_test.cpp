// The HLSL emitter: golden text for the tiny set, and for every built-in variant in every form and
// numerics, the HLSL function is the GLSL one with only the names shader_dialect.h lists changed,
// line for line, so it performs the same operations in the same order. (gpu_hlsl_test.cpp runs it.)
#include "generator/clip_emitter.h"
#include "generator/variant_spec.h"
#include "tests/emitter_specs.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <sstream>

namespace kdop {
namespace {

VariantSpec tiny(Mode mode, Neighborhood n) { return test::tiny_spec(mode, n); }

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

// A GLSL line written as HLSL by plain substitution, written here independently of the emitter's
// Dialect: vecN -> floatN, ivecN -> intN, fma -> mad, floatBitsToInt -> asint, [[unroll]] ->
// [unroll], a one-argument vector constructor (a broadcast) -> a cast, vec3[]( ... ); -> { ... };
std::string glsl_line_as_hlsl(std::string line) {
    static const std::vector<std::pair<std::regex, std::string>> rules = {
        {std::regex(R"(vec(\d)\((max\(t, 0\.0\))\))"), "(float$1)$2"}, // the paper's fma(vec3(max(t, 0.0)), ...)
        {std::regex(R"(\bvec(\d)\(([\w.]+)\))"), "(float$1)$2"},       // vec3(t), vec2(9.0)
        {std::regex(R"(\bvec(\d)\[\]\($)"), "{"},                      // the loop form's axis array
        {std::regex(R"(^(\s*)\);$)"), "$1};"},                         // and its end
        {std::regex(R"(\bivec(\d)\b)"), "int$1"},
        {std::regex(R"(\bvec(\d)\b)"), "float$1"},
        {std::regex(R"(\bfma\()"), "mad("},
        {std::regex(R"(\bfloatBitsToInt\()"), "asint("},
        {std::regex(R"(\[\[unroll\]\] )"), "[unroll] "},
        {std::regex(R"(_GLSL\b)"), "_HLSL"}, // the include guard
    };
    for (const auto& [pattern, replacement] : rules) line = std::regex_replace(line, pattern, replacement);
    return line;
}

void expect_hlsl_is_the_glsl_translated(const VariantSpec& spec) {
    std::vector<std::string> glsl = lines(emit_function(spec, kGlsl));
    const std::vector<std::string> hlsl = lines(emit_function(spec, kHlsl));
    SCOPED_TRACE(variant_name(spec));
    // The loop form's GLSL enables the extension its [[unroll]] needs, a line HLSL has no use for.
    const auto extension = std::ranges::find(glsl, "#extension GL_EXT_control_flow_attributes : enable");
    EXPECT_EQ(extension != glsl.end(), spec.form == Form::loop);
    if (extension != glsl.end()) glsl.erase(extension);
    ASSERT_EQ(glsl.size(), hlsl.size());
    for (std::size_t i = 0; i < glsl.size(); ++i) {
        // The loop form's header says what its [[unroll]] needs, which differs by language.
        if (glsl[i].find("GL_EXT_control_flow_attributes") != std::string::npos) {
            EXPECT_NE(hlsl[i].find("its loops carry [unroll]"), std::string::npos) << hlsl[i];
            continue;
        }
        EXPECT_EQ(hlsl[i], glsl_line_as_hlsl(glsl[i])) << "line " << i + 1 << ", GLSL: " << glsl[i];
    }
}

TEST(HlslEmitter, GoldenClipFunction) {
    test::expect_golden("tiny-clip-n5.hlsl", emit_function(tiny(Mode::clip, Neighborhood::n5), kHlsl));
}

TEST(HlslEmitter, GoldenVarclipFunction) {
    test::expect_golden("tiny-varclip-n5.hlsl", emit_function(tiny(Mode::varclip, Neighborhood::n5), kHlsl));
}

TEST(HlslEmitter, SignaturesUseHlslTypes) {
    auto signature_of = [](const std::string& set, Mode mode) {
        auto s = resolve_axis_set(set);
        EXPECT_TRUE(s);
        const std::string text = emit_function({*s, mode, Neighborhood::n9}, kHlsl);
        const std::size_t open = text.find("\nfloat3 ");
        return open == std::string::npos ? text : text.substr(open + 1, text.find('\n', open + 1) - open - 1);
    };
    EXPECT_EQ(signature_of("dop32", Mode::clip),
              "float3 kdop_dop32_clip_n9(float3 current, float3 history, float3 neighborhood[9])");
    EXPECT_EQ(signature_of("dop32", Mode::varclip),
              "float3 kdop_dop32_varclip_n9(float3 current, float3 history, float gamma, float3 neighborhood[9])");
}

TEST(HlslEmitter, EveryBuiltinVariantIsItsGlslWithHlslNames) {
    ASSERT_GE(all_builtin_variants().size(), 51u) << "24 defaults in two forms and three baselines";
    for (const VariantSpec& spec : test::builtin_variants_in_both_numerics()) expect_hlsl_is_the_glsl_translated(spec);
}

// The translation rules above are not vacuous: they change what the emitter writes differently.
TEST(HlslEmitter, TheComparisonSeesEachRename) {
    EXPECT_EQ(glsl_line_as_hlsl("    vec3 c0 = fma(neighborhood[0], vec3(scale), origin);"),
              "    float3 c0 = mad(neighborhood[0], (float3)scale, origin);");
    EXPECT_EQ(glsl_line_as_hlsl("        t = min(t, (floatBitsToInt(d) < 0 ? lo : hi) / d);"),
              "        t = min(t, (asint(d) < 0 ? lo : hi) / d);");
    EXPECT_EQ(glsl_line_as_hlsl("    [[unroll]] for (int a = 0; a < 3; ++a)"),
              "    [unroll] for (int a = 0; a < 3; ++a)");
    EXPECT_NE(emit_function(tiny(Mode::varclip, Neighborhood::n9), kGlsl),
              emit_function(tiny(Mode::varclip, Neighborhood::n9), kHlsl));
}

} // namespace
} // namespace kdop
