// The GLSL emitter: golden text for a tiny set that exercises every folding rule, and structural
// properties of the real sets' text (no loops, no run-time indexing, zeros and units folded).
#include "core/read_file.h"
#include "generator/clip_emitter.h"
#include "generator/compute_shader.h"
#include "generator/scaled_axis.h"
#include "generator/variant_builder.h"
#include "generator/variant_files.h"
#include "generator/variant_spec.h"
#include "tests/test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

namespace kdop {
namespace {
namespace fs = std::filesystem;

VariantSpec spec(const std::string& set, Mode mode, Neighborhood n) {
    auto axis_set = resolve_axis_set(set);
    EXPECT_TRUE(axis_set) << axis_set.error().message;
    return {*axis_set, mode, n};
}

VariantSpec tiny(Mode mode, Neighborhood n) { return spec(test::data_path("tiny.axes"), mode, n); }

// The one list of languages (generator/shader_languages.def), read as CMake reads it: a built
// variant carries a function per line, and its files are named with those extensions, in order.
TEST(Emitter, EveryLanguageOfTheListIsWrittenAndNamedByIt) {
    const auto list = read_file(fs::path(KDOP_SOURCE_DIR) / "generator/shader_languages.def");
    ASSERT_TRUE(list);
    std::vector<std::string> extensions;
    const std::regex line(R"(^KDOP_SHADER_LANGUAGE\(([a-z0-9]+),)", std::regex::multiline);
    for (std::sregex_iterator m(list->begin(), list->end(), line), end; m != end; ++m)
        extensions.push_back("." + (*m)[1].str());
    ASSERT_EQ(extensions, (std::vector<std::string>{".glsl", ".hlsl", ".wgsl"}));

    auto built = build_variant(tiny(Mode::clip, Neighborhood::n9));
    ASSERT_TRUE(built) << built.error().message;
    const std::vector<OutputFile> files = function_files(*built, "out");
    ASSERT_EQ(files.size(), extensions.size());
    for (std::size_t i = 0; i < files.size(); ++i) {
        EXPECT_EQ(files[i].path, fs::path("out") / (built->name + extensions[i]));
        EXPECT_EQ(files[i].content, emit_function(built->spec, *kShaderLanguages[i].dialect));
        EXPECT_EQ(&built->function(*kShaderLanguages[i].dialect), &built->functions[i]);
    }
    EXPECT_NE(built->function(kGlsl), built->function(kHlsl));
}

TEST(Emitter, GoldenClipFunction) {
    test::expect_golden("tiny-clip-n5.glsl", emit_function(tiny(Mode::clip, Neighborhood::n5)));
}

TEST(Emitter, GoldenVarclipFunction) {
    test::expect_golden("tiny-varclip-n5.glsl", emit_function(tiny(Mode::varclip, Neighborhood::n5)));
}

TEST(Emitter, ScalesEachAxisSoItsLargestComponentIsPlusOne) {
    ScaledAxis a = scale_axis({0, -2, 0});
    EXPECT_EQ(a.coefficients, glm::vec3(0, 1, 0));
    EXPECT_EQ(a.factor, -0.5);
    EXPECT_FLOAT_EQ(a.padding, 1e-5f); // |(0,-2,0)| x 0.5: the padding stays 1e-5 per unit length

    ScaledAxis b = scale_axis({0.656800, -0.655635, 0.372501});
    EXPECT_EQ(b.coefficients.x, 1.0f);
    EXPECT_FLOAT_EQ(b.coefficients.y, static_cast<float>(-0.655635 / 0.656800));
    EXPECT_FALSE(std::signbit(scale_axis({0, 0.6, -0.8}).coefficients.x)) << "zero must stay +0 after flipping";
}

TEST(Emitter, FoldsZeroAndUnitComponents) {
    std::string text = emit_function(tiny(Mode::clip, Neighborhood::n9));
    EXPECT_NE(text.find("float q0 = c0.x;"), std::string::npos);
    EXPECT_NE(text.find("float q0 = c0.y;"), std::string::npos);                        // (0, -2, 0) flipped and scaled
    EXPECT_NE(text.find("float q0 = c0.x - c0.z;"), std::string::npos);                 // (0.5, 0, -0.5)
    EXPECT_NE(text.find("float q0 = c0.y + (c0.x + c0.z) * -0.5;"), std::string::npos); // one scale, one multiply
    EXPECT_NE(text.find("float q0 = c0.z + c0.y * -0.75;"), std::string::npos);
}

// Properties every default variant's function must have; checked on the text itself.
void expect_fully_folded_and_unrolled(const std::string& name, const std::string& text) {
    SCOPED_TRACE(name);
    std::string code = std::regex_replace(text, std::regex("//[^\n]*"), "");
    EXPECT_EQ(code.find("for"), std::string::npos);
    EXPECT_EQ(code.find("while"), std::string::npos);
    // Arrays are read only at literal indices.
    EXPECT_FALSE(std::regex_search(code, std::regex(R"(\[[^\]0-9])"))) << "run-time array index";
    // No multiply by zero or one, no zero or unit component inside a constant vector.
    const std::string zero_or_unit = R"(-?(0|1)(\.0*)?(e[-+]?\d+)?)";
    EXPECT_FALSE(std::regex_search(code, std::regex(R"(\*\s*)" + zero_or_unit + R"(\b(?![.\d]))")))
        << "multiply by a 0 or 1 literal";
    std::smatch vector;
    std::regex constant_vector(R"(vec[234]\(([-0-9.e, ]+)\))");
    for (auto it = std::sregex_iterator(code.begin(), code.end(), constant_vector); it != std::sregex_iterator();
         ++it) {
        std::string components = (*it)[1];
        EXPECT_FALSE(std::regex_search(components, std::regex(R"((^|,)\s*)" + zero_or_unit + R"(\s*(,|$))")))
            << "constant vector with a 0 or +-1 component: " << it->str();
    }
}

TEST(Emitter, DefaultVariantsAreFullyFoldedAndUnrolled) {
    auto specs = select_variants({}, {}, {});
    ASSERT_TRUE(specs);
    for (const VariantSpec& s : *specs) expect_fully_folded_and_unrolled(variant_name(s), emit_function(s));
}

TEST(Emitter, Dop22HasNoMultiplyByZeroAndNoZeroInAConstantVector) {
    // dop22 is the set with explicit 0.000000 components; the general check above covers it, this
    // pins that its text really contains folded projections of such axes.
    std::string text = emit_function(spec("dop22", Mode::clip, Neighborhood::n9));
    expect_fully_folded_and_unrolled("dop22-clip-n9", text);
    // Axes (0, 0.664104, -0.747640) and (-0.664672, 0, 0.747135): one multiply-add each, the
    // coefficient being the published ratio rounded to float.
    auto literal = [](double ratio) { return fmt::format("{}", static_cast<float>(ratio)); };
    EXPECT_NE(text.find("float q0 = c0.z + c0.y * " + literal(0.664104 / -0.747640) + ";"), std::string::npos);
    EXPECT_NE(text.find("float q0 = c0.z + c0.x * " + literal(-0.664672 / 0.747135) + ";"), std::string::npos);
}

TEST(Emitter, ComputeShaderFillsEveryPlaceholderAndCallsTheFunction) {
    auto templ = "@VARIANT@|@NEIGHBOR_COUNT@|@CALL@";
    auto text = emit_compute_shader(spec("aabb", Mode::varclip, Neighborhood::n5), templ, "t.in");
    ASSERT_TRUE(text) << text.error().message;
    EXPECT_EQ(*text,
              "aabb-varclip-n5|5|kdop_aabb_varclip_n5(neighborhood[2], history, parameters.gamma, neighborhood)");
}

TEST(Emitter, TemplateErrorsNameTheLine) {
    auto s = spec("aabb", Mode::clip, Neighborhood::n9);
    EXPECT_EQ(emit_compute_shader(s, "a\nb @NOPE@\n", "t.in").error().message, "t.in:2: unknown placeholder @NOPE@");
    EXPECT_EQ(emit_compute_shader(s, "a\n\nb @VARIANT\n", "t.in").error().message,
              "t.in:3: unterminated placeholder (a '@' without its closing '@')");
}

// Text from outside reaches generated code only inside comments, and cannot end them: a file name
// with a line break (the parser refuses control characters in a file's text, not in its name).
TEST(Emitter, FileNamesCannotEndTheCommentsTheyAreQuotedIn) {
    VariantSpec s = tiny(Mode::clip, Neighborhood::n9);
    s.set.origin = "evil\nlayout(binding = 9) buffer B { float b; };\n.axes";
    for (const std::string& text : {emit_function(s), emit_function([&] {
                                        VariantSpec loop = s;
                                        loop.form = Form::loop;
                                        return loop;
                                    }())})
        for (std::size_t start = 0, end; start < text.size(); start = end + 1) {
            end = text.find('\n', start);
            const std::string line = text.substr(start, end - start);
            EXPECT_TRUE(line.find("binding = 9") == std::string::npos || line.find("//") < line.find("binding = 9"))
                << "code outside a comment: " << line;
        }
}

// Every form takes the axes at the same scale: a set of tiny axes (1e-50, whose float32 is 0) and
// one of huge axes (1e39, whose float32 is infinite) give finite, nonzero literals in the loop form
// as in the unrolled one.
TEST(Emitter, AxesFarFromUnitLengthReachEveryFormScaled) {
    for (const char* axes :
         {"1e-50 2e-50 3e-50\n-1e-50 1e-50 0\n0 0 1e-50\n", "1e39 2e39 3e39\n-1e39 1e39 0\n0 0 1e39\n",
          "1 0 0\n0 1 0\n0 0 1e-310\n2e-310 1e-310 0\n"}) { // and denormal components
        auto set = parse_axis_set(std::string("name: far\nprovenance: test\n") + axes, "far.axes");
        ASSERT_TRUE(set) << set.error().message;
        for (Form form : {Form::unrolled, Form::loop}) {
            VariantSpec spec{*set, Mode::clip, Neighborhood::n9, form};
            const std::string text = emit_function(spec);
            EXPECT_EQ(text.find("vec3(0.0, 0.0, 0.0)"), std::string::npos) << axes << to_string(form) << text;
            EXPECT_EQ(text.find("inf"), std::string::npos) << axes << to_string(form) << text;
            EXPECT_EQ(text.find("nan"), std::string::npos) << axes << to_string(form) << text;
            auto built = build_variant(spec);
            EXPECT_TRUE(built) << axes << to_string(form) << ": " << built.error().message;
        }
    }
}

// The output depends on the spec alone: a set parsed afresh, after other variants were emitted,
// gives the same bytes (no state carried between calls), and changing one axis changes them.
TEST(Emitter, OutputIsAPureFunctionOfTheSpec) {
    const std::string first = emit_function(spec("dop32", Mode::varclip, Neighborhood::n9));
    const auto others = select_variants({"aabb", "dop22"}, {}, {});
    ASSERT_TRUE(others);
    for (const VariantSpec& other : *others) emit_function(other);
    EXPECT_EQ(emit_function(spec("dop32", Mode::varclip, Neighborhood::n9)), first);
    VariantSpec changed = spec("dop32", Mode::varclip, Neighborhood::n9);
    changed.set.axes.back().direction.x += 0.125;
    EXPECT_NE(emit_function(changed), first);
}

} // namespace
} // namespace kdop
