// kdop-gen and the files it reads against the inputs of an adversarial run (issue 58): shader names
// glslang must carry as names, never as code; names the registry cannot hold; an include bomb; text
// JSON cannot hold; a manifest's `set:` line outside its folder. Each test failed before its fix.
#include "core/utf8.h"
#include "fit/fitted_set.h"
#include "generator/reflection_json.h"
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

} // namespace
} // namespace kdop
