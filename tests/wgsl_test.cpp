// The WGSL emitter: golden text for the tiny set; every built-in variant's WGSL function, in every
// form and numerics, compiled inside a compute shader by Tint (Dawn's WGSL compiler, through the
// webgpu package install-deps.sh puts in tests/wgsl; tint_check.mjs); a broken one refused with
// Tint's message; and each function's operations, counted per kind, the GLSL function's.
#include "generator/clip_emitter.h"
#include "generator/variant_spec.h"
#include "tests/emitter_specs.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <regex>

namespace kdop {
namespace {

namespace fs = std::filesystem;

VariantSpec tiny(Mode mode, Neighborhood n) { return test::tiny_spec(mode, n); }
std::vector<VariantSpec> every_variant() { return test::builtin_variants_in_both_numerics(); }

// The function inside a compute shader that reads its inputs from, and writes its result to, a
// storage buffer, so that nothing of it is dead code.
std::string in_compute_shader(const VariantSpec& spec, const std::string& function) {
    const std::size_t count = neighborhood_offsets(spec.neighborhood).size();
    return function + fmt::format(R"(
@group(0) @binding(0) var<storage, read_write> colors: array<vec4f, {0}>;

@compute @workgroup_size(1)
fn main()
{{
    var neighborhood: array<vec3f, {1}>;
    for (var i = 0; i < {1}; i++) {{ neighborhood[i] = colors[i].xyz; }}
    colors[{2}] = vec4f({3}(neighborhood[{4}], colors[{1}].xyz, {5}neighborhood), 1.0);
}}
)",
                                  count + 2, count, count + 1, glsl_function_name(spec),
                                  neighborhood_center(spec.neighborhood),
                                  spec.mode == Mode::varclip ? "colors[0].w, " : "");
}

// Tint's verdict on one file (see tests/wgsl/tint_check.mjs).
test::CommandResult tint(const fs::path& file) {
    return test::run(fmt::format("'{}' '{}' '{}'", KDOP_NODE, KDOP_TINT_CHECK, file.string()));
}

class TintCompiles : public ::testing::Test {
protected:
    void SetUp() override {
        const fs::path webgpu = fs::path(KDOP_TINT_CHECK).parent_path() / "node_modules" / "webgpu";
        if (std::string(KDOP_NODE).empty() || !fs::exists(webgpu))
            FAIL() << "node or " << webgpu << " is missing: run ./install-deps.sh, which installs both";
    }
};

TEST_F(TintCompiles, EveryVariantsFunction) {
    test::TempDir dir;
    const std::vector<VariantSpec> specs = every_variant();
    ASSERT_GE(specs.size(), 99u) << "51 built-in variants, 48 of them also with the paper's numerics";
    for (const VariantSpec& spec : specs) {
        const std::string name = variant_name(spec);
        const fs::path file = dir / (name + ".wgsl");
        test::write_file(file, in_compute_shader(spec, emit_function(spec, kWgsl)));
        const test::CommandResult r = tint(file);
        EXPECT_EQ(r.exit_code, 0) << name << ":\n" << r.out << r.err;
        EXPECT_NE(r.out.find(": ok"), std::string::npos) << name << ":\n" << r.out;
    }
}

TEST_F(TintCompiles, ABrokenFunctionFailsWithTintsMessage) {
    test::TempDir dir;
    auto dop22 = resolve_axis_set("dop22");
    ASSERT_TRUE(dop22);
    const VariantSpec spec{*dop22, Mode::clip, Neighborhood::n9};
    std::string broken = in_compute_shader(spec, emit_function(spec, kWgsl));
    const std::size_t at = broken.find("select(");
    ASSERT_NE(at, std::string::npos);
    broken.replace(at, 6, "choose");
    const int line = 1 + static_cast<int>(std::count(broken.begin(), broken.begin() + at, '\n'));
    const fs::path file = dir / "broken.wgsl";
    test::write_file(file, broken);
    const test::CommandResult r = tint(file);
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_NE(r.out.find(fmt::format("broken.wgsl:{}:", line)), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("error: unresolved call target 'choose'"), std::string::npos) << r.out;
}

// The operations a function's body spells, per kind: each call by name (fma and mad, and
// floatBitsToInt, asint and bitcast<i32>, and vecN and vecNf, as one), the conditional (?: and
// select as one), each arithmetic, comparison and logical operator (a compound assignment as its
// operator), and negation. Written here from the languages, not from the emitter's Dialect.
std::map<std::string, int> operations(std::string text) {
    text = std::regex_replace(text, std::regex(R"(//[^\n]*)"), "");
    text = std::regex_replace(text, std::regex(R"(\n#[^\n]*)"), "\n"); // include guard, extension
    text = text.substr(text.find("\n{"));                              // the body
    text = std::regex_replace(text, std::regex(R"(array<vec(\d)f, \d+>\()"), "vec$1[](");
    text = std::regex_replace(text, std::regex(R"(\bbitcast<i32>\()"), "floatBitsToInt(");
    const std::regex token(
        R"(([A-Za-z_]\w*)\s*(\()?|(\d+\.?\d*(?:[eE][+-]?\d+)?)|(<=|>=|==|!=|&&|\|\||\+\+|[-+*/]=|[-+*/<>?(),=;:{}\[\].!]))");
    std::map<std::string, int> count;
    std::string previous = "(";
    for (auto it = std::sregex_iterator(text.begin(), text.end(), token); it != std::sregex_iterator(); ++it) {
        const std::smatch& m = *it;
        std::string kind;
        if (m[1].matched) {
            std::string name = m[1];
            if (m[2].matched) {
                name = std::regex_replace(name, std::regex(R"(^(vec\d)f$)"), "$1");
                kind = name == "mad" ? "fma" : name == "asint" ? "floatBitsToInt" : name;
                count[kind == "select" ? "?" : kind + "()"]++;
                previous = "(";
                continue;
            }
            previous = name == "return" ? "(" : "value";
            continue;
        }
        if (m[3].matched) {
            previous = "value";
            continue;
        }
        std::string op = m[4];
        if (op == "-" && previous != "value" && previous != ")" && previous != "]") op = "negate";
        if (op.size() == 2 && op[1] == '=' && std::string("+-*/").find(op[0]) != std::string::npos)
            op = op.substr(0, 1);
        if (std::string("(),=;:{}[].").find(op) == std::string::npos || op == "?") count[op]++;
        previous = op == ")" || op == "]" ? op : "(";
    }
    return count;
}

TEST(WgslOperations, AreTheGlslFunctionsPerKind) {
    for (const VariantSpec& spec : every_variant()) {
        const auto glsl = operations(emit_function(spec, kGlsl));
        const auto wgsl = operations(emit_function(spec, kWgsl));
        EXPECT_EQ(wgsl, glsl) << variant_name(spec);
    }
    // Not vacuous: the hardened 22-DOP clip's body has each kind the comparison relies on.
    auto dop22 = resolve_axis_set("dop22");
    ASSERT_TRUE(dop22);
    auto ops = operations(emit_function({*dop22, Mode::clip, Neighborhood::n9}, kWgsl));
    for (const char* kind : {"min()", "max()", "fma()", "abs()", "floatBitsToInt()", "?", "+", "-", "/", "<", "<="})
        EXPECT_GT(ops[kind], 0) << kind;
    // and a one-operator change is seen.
    const std::string text = emit_function({*dop22, Mode::clip, Neighborhood::n9}, kWgsl);
    std::string changed = text;
    changed.replace(changed.find("reach.x + reach.y"), 17, "reach.x * reach.y");
    EXPECT_NE(operations(changed), operations(text));
}

TEST(WgslEmitter, GoldenClipFunction) {
    test::expect_golden("tiny-clip-n5.wgsl", emit_function(tiny(Mode::clip, Neighborhood::n5), kWgsl));
}

TEST(WgslEmitter, GoldenVarclipFunction) {
    test::expect_golden("tiny-varclip-n5.wgsl", emit_function(tiny(Mode::varclip, Neighborhood::n5), kWgsl));
}

TEST(WgslEmitter, SignaturesAreTheGlslOnesInWgsl) {
    auto dop32 = resolve_axis_set("dop32");
    ASSERT_TRUE(dop32);
    const std::string clip = emit_function({*dop32, Mode::clip, Neighborhood::n9}, kWgsl);
    EXPECT_NE(
        clip.find("\nfn kdop_dop32_clip_n9(current: vec3f, history: vec3f, neighborhood: array<vec3f, 9>) -> vec3f\n"),
        std::string::npos)
        << clip;
    const std::string varclip = emit_function({*dop32, Mode::varclip, Neighborhood::n5}, kWgsl);
    EXPECT_NE(varclip.find("\nfn kdop_dop32_varclip_n5(current: vec3f, history: vec3f, gamma: f32, neighborhood: "
                           "array<vec3f, 5>) -> vec3f\n"),
              std::string::npos)
        << varclip;
    EXPECT_EQ(clip.find('#'), std::string::npos) << "WGSL has no preprocessor";
}

} // namespace
} // namespace kdop
