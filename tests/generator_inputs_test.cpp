// kdop-gen and the files it reads against the inputs of an adversarial run (issue 58): shader names
// glslang must carry as names, never as code; names the registry cannot hold; an include bomb; text
// JSON cannot hold; a manifest's `set:` line outside its folder. Each test failed before its fix.
#include "core/utf8.h"
#include "fit/fitted_set.h"
#include "generator/manifest.h"
#include "generator/reflection_json.h"
#include "generator/source_names.h"
#include "generator/variant_builder.h"
#include "tests/test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <string>

namespace kdop {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::json;

// `path` as one word of a POSIX shell, whatever it holds.
std::string shell_word(const fs::path& path) {
    std::string out = "'";
    for (char c : path.string()) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// `kdop-gen registry` of dop22-clip-n9 and `shaders`, written as JSON to `json`.
test::CommandResult registry_json(const std::vector<fs::path>& shaders, const fs::path& json,
                                  const std::string& more = "") {
    std::string command = fmt::format("{} registry --sets dop22 --modes clip --neighborhoods n9 --json {} {}",
                                      test::kdop_gen_binary(), shell_word(json), more);
    if (!shaders.empty()) command += " --shaders";
    for (const fs::path& s : shaders) command.append(" ").append(shell_word(s));
    return test::run(command);
}

// A TAA resolve as the adversarial run took it: the clip included, the history blended with mix().
constexpr const char* kResolve = R"(#version 450
#include "dop22-clip-n9.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D current_frame;
layout(set = 0, binding = 1) uniform sampler2D history_frame;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D resolved_frame;
void main()
{
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    vec3 n[9];
    for (int i = 0; i < 9; ++i) n[i] = texelFetch(current_frame, p + ivec2(i % 3 - 1, i / 3 - 1), 0).rgb;
    const vec3 clipped = kdop_dop22_clip_n9(n[4], texelFetch(history_frame, p, 0).rgb, n);
    imageStore(resolved_frame, p, vec4(mix(clipped, n[4], 0.1), 1.0));
}
)";

// The same in HLSL, whose front end writes the same #line.
constexpr const char* kResolveHlsl = R"(#include "dop22-clip-n9.hlsl"
Texture2D<float4> current_frame : register(t1);
SamplerState point_sampler : register(s2);
RWTexture2D<float4> resolved : register(u0, space1);
[numthreads(8, 8, 1)]
void main(uint3 id : SV_DispatchThreadID)
{
    float3 n[9];
    for (int i = 0; i < 9; ++i)
        n[i] = current_frame.Load(int3(id.xy + uint2(i % 3, i / 3), 0)).rgb;
    resolved[id.xy] = float4(lerp(kdop_dop22_clip_n9(n[4], float3(0, 0, 0), n), n[4], 0.1), 1);
}
)";

const Json* entry_named(const Json& document, const std::string& name) {
    for (const Json& e : document["entries"])
        if (e["name"] == name) return &e;
    return nullptr;
}

// glslang writes `#line N "<shader>"` after an #include with the name unescaped: this name made the
// resolve `mix(a, b, c) = b`, with no clip and no history (561 words instead of 3,625, the
// history_frame binding gone), and exit 0. Now every name compiles to the same code as a plain one,
// and names the shader, as it is, in messages.
TEST(GeneratorInputs, AShaderNameIsNeverReadAsCode) {
    test::TempDir dir;
    const fs::path plain = dir / "taa.comp";
    test::write_file(plain, kResolve);
    const std::vector<std::string> names = {"e\"\n#define mix(a,b,c) (b)\n#line 11 \"taa", // the injection
                                            "q\"x",                                        // gave "q:9: error: '#line'"
                                            "back\\slash",
                                            "a:b",
                                            "100%",
                                            "caf\xc3\xa9",
                                            "tab\there",
                                            "kdop-source-0"};
    std::vector<fs::path> shaders{plain};
    for (const std::string& name : names) {
        shaders.push_back(dir / (name + ".comp"));
        test::write_file(shaders.back(), kResolve);
    }
    auto r = registry_json(shaders, dir / "out.json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Json document = Json::parse(test::read_file(dir / "out.json"));
    const Json* reference = entry_named(document, "taa");
    ASSERT_TRUE(reference);
    EXPECT_EQ((*reference)["bindings"].size(), 3u);
    for (const std::string& name : names) {
        const Json* entry = entry_named(document, name);
        ASSERT_TRUE(entry) << name;
        EXPECT_EQ((*entry)["spirv"]["fnv1a64"], (*reference)["spirv"]["fnv1a64"]) << name << ": other code";
        EXPECT_EQ((*entry)["bindings"], (*reference)["bindings"]) << name;
    }

    // HLSL: lerp() for mix().
    const fs::path plain_hlsl = dir / "taa_hlsl.cs.hlsl",
                   injected_hlsl = dir / "e\"\n#define lerp(a,b,c) (b)\n#line 11 \"taa_hlsl.cs.hlsl";
    test::write_file(plain_hlsl, kResolveHlsl);
    test::write_file(injected_hlsl, kResolveHlsl);
    auto hlsl = registry_json({plain_hlsl, injected_hlsl}, dir / "hlsl.json");
    ASSERT_EQ(hlsl.exit_code, 0) << hlsl.err;
    const Json hlsl_document = Json::parse(test::read_file(dir / "hlsl.json"));
    const Json* plain_entry = entry_named(hlsl_document, "taa_hlsl");
    const Json* injected_entry = entry_named(hlsl_document, "e\"\n#define lerp(a,b,c) (b)\n#line 11 \"taa_hlsl");
    ASSERT_TRUE(plain_entry && injected_entry);
    EXPECT_EQ((*injected_entry)["spirv"]["fnv1a64"], (*plain_entry)["spirv"]["fnv1a64"]) << "other code";

    // Errors name the shader and the included file as they are, with their lines.
    fs::create_directories(dir / "we\"ird\\");
    const fs::path shader = dir / "we\"ird\\" / "a:b\"c.comp";
    test::write_file(shader, "#version 450\n#include \"blend.glsl\"\nlayout(local_size_x = 1) in;\n"
                             "void main() { vec3 x = y; }\n");
    test::write_file(dir / "we\"ird\\" / "blend.glsl", "// blend\nvec3 blend() { return z; }\n");
    auto bad = registry_json({shader}, dir / "bad.json");
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(bad.err.find((dir / "we\"ird\\" / "blend.glsl").string() + ":2: error"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(dir / "bad.json"));
}

TEST(GeneratorInputs, SourceNamesAreGlslangsOwnAndMapBack) {
    SourceNames names;
    EXPECT_EQ(names.alias("taa.comp"), "taa.comp") << "a plain name is kept, for glslang's __FILE__";
    const std::string alias = names.alias("q\"x.comp");
    EXPECT_TRUE(is_plain_source_name(alias)) << alias;
    EXPECT_EQ(names.real(alias), "q\"x.comp");
    EXPECT_EQ(names.alias("q\"x.comp"), alias) << "one source, one name";
    // A file really named as another's alias gets a name of its own.
    const std::string own = names.alias(alias);
    EXPECT_NE(own, alias);
    EXPECT_EQ(names.real(own), alias);
    for (const char* name : {"a\"b", "a\\b", "a\nb", "a:b", "caf\xc3\xa9", "x\xff", "", "50%"})
        EXPECT_FALSE(is_plain_source_name(name)) << name;
}

// `..comp` became an entry named '.'; `x\xff.comp` failed at the end with nlohmann's "invalid UTF-8
// byte", naming neither the file nor the reason. Both are refused before any work, naming the file.
TEST(GeneratorInputs, ANameTheRegistryCannotHoldIsRefusedNamingTheFile) {
    struct Case {
        std::string file, expected;
    };
    const Case cases[] = {
        {"..comp", "..comp: the registry would name this shader '.', which begins with '.'"},
        {"...frag", "...frag: the registry would name this shader '..'"},
        {".hidden.cs.hlsl", "the registry would name this shader '.hidden'"},
        {"x\xff.comp", "x\\xff.comp: the registry would name this shader 'x\\xff', whose byte 0xff is not UTF-8"},
        {"caf\xe9.vert", "caf\\xe9.vert: the registry would name this shader 'caf\\xe9'"},
    };
    for (const Case& c : cases) {
        test::TempDir dir;
        test::write_file(dir / c.file, kResolve);
        auto r = registry_json({dir / c.file}, dir / "out.json");
        EXPECT_EQ(r.exit_code, 1) << c.file;
        EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("json.exception"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir / "out.json"));
    }
}

// 25 files, each including the next twice: 2^24 includes. kdop-gen ran past a minute and 1.2 GB,
// growing; now it stops at the limit within seconds, naming the shader and the limit. The same
// files guarded against a second include compile.
TEST(GeneratorInputs, AnIncludeBombIsStoppedAtTheLimit) {
    for (const bool guarded : {false, true}) {
        test::TempDir dir;
        const fs::path shader = dir / "bomb.comp";
        test::write_file(shader, "#version 450\n#include \"b0.glsl\"\nlayout(local_size_x = 1) in;\nvoid main() {}\n");
        for (int i = 0; i < 25; ++i) {
            const std::string next = i + 1 < 25 ? fmt::format("#include \"b{0}.glsl\"\n#include \"b{0}.glsl\"\n", i + 1)
                                                : std::string("// the last\n");
            test::write_file(dir / fmt::format("b{}.glsl", i),
                             guarded ? fmt::format("#ifndef B{0}\n#define B{0}\n{1}#endif\n", i, next) : next);
        }
        const auto start = std::chrono::steady_clock::now();
        auto r = test::run("timeout 60 " + test::kdop_gen_binary() +
                           " registry --sets dop22 --modes clip --neighborhoods n9 --json " +
                           (dir / "out.json").string() + " --shaders " + shader.string());
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (guarded) {
            EXPECT_EQ(r.exit_code, 0) << r.err;
            continue;
        }
        EXPECT_EQ(r.exit_code, 1) << r.err;
        EXPECT_LT(seconds, 30) << "the limit is reached in seconds";
        EXPECT_NE(r.err.find(shader.string() + ": more than 10000 includes, kdop's limit for one shader"),
                  std::string::npos)
            << r.err.substr(0, 2000);
        EXPECT_NE(r.err.find("guard each with #ifndef"), std::string::npos) << r.err.substr(0, 2000);
        EXPECT_LT(r.err.size(), 4000u) << "one message, not one an include";
        EXPECT_FALSE(fs::exists(dir / "out.json"));
    }
    // The text they bring in is limited too: 17 includes of 1 MiB.
    test::TempDir dir;
    std::string includes;
    for (int i = 0; i < 17; ++i) includes += fmt::format("#include \"big{}.glsl\"\n", i);
    for (int i = 0; i < 17; ++i) test::write_file(dir / fmt::format("big{}.glsl", i), std::string(1 << 20, '\n'));
    test::write_file(dir / "big.comp", "#version 450\n" + includes + "layout(local_size_x = 1) in;\nvoid main() {}\n");
    auto r = registry_json({dir / "big.comp"}, dir / "out.json");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("big.comp: more than 16 MiB of included text, kdop's limit"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("big16.glsl"), std::string::npos) << "the include that went past it: " << r.err;
}

// A Latin-1 provenance was accepted, then `kdop gen` and `kdop-gen --json` failed at the end with
// nlohmann's exception, naming neither file nor line. It is refused where the file is read.
TEST(GeneratorInputs, AnAxisFileThatIsNotUtf8IsRefusedNamingItsLine) {
    test::TempDir dir;
    const fs::path axes = dir / "latin1.axes";
    test::write_file(axes, "name: latin\nprovenance: caf\xe9\n1 0 0\n0 1 0\n0 0 1\n");
    const std::string expected = axes.string() + ":2: byte 0xe9 (column 16) is not UTF-8";
    auto gen = test::run(test::kdop_gen_binary() + " registry --sets " + axes.string() +
                         " --modes clip --neighborhoods n9 --json " + (dir / "out.json").string());
    EXPECT_EQ(gen.exit_code, 1);
    EXPECT_NE(gen.err.find(expected), std::string::npos) << gen.err;
    auto cli = test::run(test::kdop_binary() + " gen --sets " + axes.string() + " --modes clip --neighborhoods n9 " +
                         "--out " + (dir / "gen").string());
    EXPECT_NE(cli.exit_code, 0);
    EXPECT_NE(cli.err.find(expected), std::string::npos) << cli.err;
    EXPECT_FALSE(fs::exists(dir / "out.json"));
    EXPECT_FALSE(fs::exists(dir / "gen"));

    // The JSON names .spv files by their path, which must be UTF-8 too: a usage error, before any work.
    auto spirv = registry_json({}, dir / "out.json", "--spirv-dir " + (dir / "sp\xffv").string());
    EXPECT_EQ(spirv.exit_code, 2) << spirv.err;
    EXPECT_NE(spirv.err.find("--spirv-dir: "), std::string::npos) << spirv.err;
    EXPECT_NE(spirv.err.find("sp\\xffv/x.spv', which is not UTF-8"), std::string::npos) << spirv.err;

    // And the JSON writer, the last line, writes what might still slip through instead of throwing.
    BuiltVariant v;
    v.name = "x\xff";
    v.spec.mode = Mode::clip;
    v.spec.neighborhood = Neighborhood::n9;
    v.spec.set = {.name = "s", .provenance = "caf\xe9", .origin = "s.axes", .axes = {{{1, 0, 0}, 1}}};
    std::string json;
    ASSERT_NO_THROW(json = reflection_json(std::span(&v, 1), {}));
    EXPECT_EQ(Json::parse(json)["entries"][0]["clip"]["axis_set"]["provenance"], "caf\xef\xbf\xbd");
}

// A fitted set's provenance and comments name its inputs, whose paths may hold any byte: written as
// \xNN where they are not UTF-8 text, so the set refused above never comes from kdop itself.
TEST(GeneratorInputs, AFittedSetNamingAnyInputIsAnAxisFileKdopReads) {
    const FittedSetText text{"fitted3", "fitted to caf\xe9/a.exr\nname: x", {"from caf\xe9", "caf\xc3\xa9"}, {}};
    const std::vector<glm::dvec3> axes{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    auto file = fitted_set_file(text, axes);
    ASSERT_TRUE(file) << file.error().message;
    auto set = parse_axis_set(*file, "fitted3.axes");
    ASSERT_TRUE(set) << set.error().message;
    EXPECT_EQ(set->provenance, "fitted to caf\\xe9/a.exr\\x0aname: x");
    EXPECT_NE(file->find("# from caf\\xe9\n# caf\xc3\xa9\n"), std::string::npos) << *file;
    EXPECT_EQ(utf8_line("tab\tcaf\xc3\xa9\x1b\xff"), "tab\tcaf\xc3\xa9\\x1b\\xff");
}

// A manifest's `set:` line read any file and echoed its lines in errors ("/etc/passwd:1: unknown key
// 'root'"). It is confined as a shader's includes are: to the manifest's folder and below it.
TEST(GeneratorInputs, AManifestReadsSetFilesOnlyFromItsFolder) {
    test::TempDir dir;
    fs::create_directories(dir / "level" / "axes");
    constexpr const char* kSet = "name: forest\nprovenance: a test\n1 0 0\n0 1 0\n0 0 1\n";
    test::write_file(dir / "level" / "axes" / "forest.axes", kSet);
    test::write_file(dir / "outside.axes", "root:x:0:0:root:/root:/bin/bash\n");
    fs::create_symlink(dir / "outside.axes", dir / "level" / "link.axes");
    const std::vector<std::string> outside = {"/etc/passwd", "../outside.axes", "axes/../../outside.axes", "link.axes",
                                              (dir / "outside.axes").string()};
    for (const std::string& named : outside) {
        test::write_file(dir / "level" / "scene.manifest", "set: " + named + "\nforest-clip-n9\n");
        auto m = read_manifest(dir / "level" / "scene.manifest");
        ASSERT_FALSE(m) << named;
        EXPECT_NE(m.error().message.find("scene.manifest:1: `set: " + named +
                                         "` names a file outside the "
                                         "manifest's folder"),
                  std::string::npos)
            << m.error().message;
        EXPECT_EQ(m.error().message.find("root"), std::string::npos) << "nothing of the file: " << m.error().message;
    }
    test::write_file(dir / "level" / "scene.manifest", "set: axes/forest.axes\nforest-clip-n9\n");
    auto inside = read_manifest(dir / "level" / "scene.manifest");
    ASSERT_TRUE(inside) << inside.error().message;
    const fs::path absolute = fs::absolute(dir / "level" / "axes" / "forest.axes");
    test::write_file(dir / "level" / "scene.manifest", "set: " + absolute.string() + "\nforest-clip-n9\n");
    EXPECT_TRUE(read_manifest(dir / "level" / "scene.manifest")) << "an absolute path inside is inside";
}

} // namespace
} // namespace kdop
