// The kdop command line, run as a user runs it: list, gen and show, bad input refused with a
// message naming the file/line or argument, a non-zero exit and nothing written.
#include "images/image_io.h"
#include "reference/cpu_clip.h"
#include "tests/test_support.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <thread>

namespace kdop {
namespace {
namespace fs = std::filesystem;
using test::run;

std::string kdop(const std::string& args) { return test::kdop_binary() + " " + args; }

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

TEST(Cli, ListPrintsEveryDefaultCombinationOncePerLine) {
    auto r = run(kdop("list"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::string> expected;
    for (std::string set : {"aabb", "ycocg", "dop16-asphalt", "dop16-grass", "dop22", "dop32"})
        for (std::string mode : {"clip", "varclip"})
            for (std::string n : {"n9", "n5"}) expected.push_back(set + "-" + mode + "-" + n);
    EXPECT_EQ(lines(r.out), expected);
}

// A user's set is listed like a built-in one, with its loop forms under --all.
TEST(Cli, ListTakesTheUsersSets) {
    auto r = run(kdop("list --sets dop22 " + test::data_path("tiny.axes")));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(lines(r.out),
              (std::vector<std::string>{"dop22-clip-n9", "dop22-clip-n5", "dop22-varclip-n9", "dop22-varclip-n5",
                                        "tiny-clip-n9", "tiny-clip-n5", "tiny-varclip-n9", "tiny-varclip-n5"}));
    auto all = run(kdop("list --all --sets " + test::data_path("tiny.axes")));
    ASSERT_EQ(all.exit_code, 0) << all.err;
    EXPECT_EQ(lines(all.out).size(), 8u);
    EXPECT_NE(all.out.find("tiny-clip-n9-loop\n"), std::string::npos) << all.out;
    auto missing = run(kdop("list --sets nowhere.axes"));
    EXPECT_EQ(missing.exit_code, 2) << "a name that is neither a set nor a file is a wrong command line";
    EXPECT_NE(missing.err.find("nowhere.axes"), std::string::npos) << missing.err;
}

TEST(Cli, GenWritesGlslHlslWgslCompAndSpvPerVariantAndPrintsATable) { // and variants.json
    test::TempDir dir;
    auto r = run(kdop("gen --out " + (dir / "out").string() + " --sets dop22 " + test::data_path("tiny.axes") +
                      " --modes clip --neighborhoods n9 n5"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (std::string name : {"dop22-clip-n9", "dop22-clip-n5", "tiny-clip-n9", "tiny-clip-n5"})
        for (std::string ext : {".glsl", ".hlsl", ".wgsl", ".comp", ".spv"})
            EXPECT_TRUE(fs::exists(dir / "out" / (name + ext))) << name + ext;
    EXPECT_TRUE(fs::exists(dir / "out" / "variants.json")) << "their reflection";
    EXPECT_EQ(std::distance(fs::directory_iterator(dir / "out"), fs::directory_iterator()), 21);
    EXPECT_NE(test::read_file(dir / "out" / "dop22-clip-n9.hlsl")
                  .find("float3 kdop_dop22_clip_n9(float3 current, float3 history, float3 neighborhood[9])"),
              std::string::npos);
    EXPECT_NE(r.out.find("variant"), std::string::npos);
    EXPECT_NE(r.out.find("instructions"), std::string::npos);
    EXPECT_NE(r.out.find("dop22-clip-n9"), std::string::npos);
    // The .spv is the module's words: SPIR-V magic first.
    std::string spv = test::read_file(dir / "out" / "dop22-clip-n9.spv");
    ASSERT_GE(spv.size(), 20u);
    EXPECT_EQ(spv.substr(0, 4), std::string("\x03\x02\x23\x07", 4));
}

TEST(Cli, TwoGenerationRunsGiveIdenticalBytes) {
    test::TempDir dir;
    ASSERT_EQ(run(kdop("gen --out " + (dir / "a").string())).exit_code, 0);
    ASSERT_EQ(run(kdop("gen --threads 1 --out " + (dir / "b").string())).exit_code, 0);
    size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir / "a")) {
        ++files;
        EXPECT_EQ(test::read_file(entry.path()), test::read_file(dir / "b" / entry.path().filename()))
            << entry.path().filename();
    }
    EXPECT_EQ(files, 61u) << "12 default variants (n9, both modes) x .glsl, .hlsl, .wgsl, .comp, .spv, and "
                             "variants.json";
}

// The .spv's version word (the header's second word, little-endian) is the one --target-env asks for.
TEST(Cli, GenAndRegistryBuildForTheTargetEnvironment) {
    test::TempDir dir;
    const std::pair<const char*, std::string> envs[] = {{"", std::string("\x00\x00\x01\x00", 4)},
                                                        {"vulkan1.0", std::string("\x00\x00\x01\x00", 4)},
                                                        {"vulkan1.1", std::string("\x00\x03\x01\x00", 4)},
                                                        {"vulkan1.2", std::string("\x00\x05\x01\x00", 4)},
                                                        {"vulkan1.3", std::string("\x00\x06\x01\x00", 4)}};
    for (const auto& [env, version] : envs) {
        fs::path out = dir / (std::string("out-") + env);
        auto r = run(kdop("gen --sets aabb --modes varclip --neighborhoods n5 --out " + out.string() +
                          (*env ? std::string(" --target-env ") + env : std::string())));
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(test::read_file(out / "aabb-varclip-n5.spv").substr(4, 4), version) << env;
    }
    auto r =
        run(test::kdop_gen_binary() + " registry --sets aabb --modes clip --neighborhoods n5 --target-env " +
            "vulkan1.3 --namespace x --header " + (dir / "x.h").string() + " --source " + (dir / "x.cpp").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(test::read_file(dir / "x.cpp").find("0x00010600"), std::string::npos) << "SPIR-V 1.6 header word";
    for (const std::string& bad : {kdop("gen --out " + (dir / "bad").string() + " --target-env vulkan1.4"),
                                   test::kdop_gen_binary() + " registry --target-env opengl --namespace x --header " +
                                       (dir / "y.h").string() + " --source " + (dir / "y.cpp").string()}) {
        auto refused = run(bad);
        EXPECT_EQ(refused.exit_code, 2) << bad;
        EXPECT_NE(refused.err.find("--target-env"), std::string::npos) << refused.err;
    }
    EXPECT_FALSE(fs::exists(dir / "bad"));
    EXPECT_FALSE(fs::exists(dir / "y.cpp"));
}

// Runs `kdop gen` on an axis file with the given text; expects refusal with `message` on stderr
// and no output directory.
void expect_refused(const std::string& axes_text, const std::string& message) {
    test::TempDir dir;
    test::write_file(dir / "bad.axes", axes_text);
    fs::path out = dir / "out";
    auto r = run("cd " + dir.path().string() + " && " + kdop("gen --sets bad.axes --out " + out.string()));
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find(message), std::string::npos) << "stderr was: " << r.err;
    EXPECT_FALSE(fs::exists(out)) << "output written despite the error";
}

TEST(Cli, GenRefusesBadAxisFilesAndWritesNothing) {
    const std::string header = "name: bad\nprovenance: test\n";
    expect_refused(header + "1 0 0\n0 1 x\n0 0 1\n", "bad.axes:4: 'x' is not a number");
    expect_refused(header + "1 0 0\n0 1\n0 0 1\n", "bad.axes:4: expected 3 numbers (x y z), found 2");
    expect_refused(header + "1 0 0\n0 0 0\n0 0 1\n", "bad.axes:4: axis has zero length");
    expect_refused(header + "1 0 0\nnan 1 0\n0 0 1\n", "bad.axes:4: axis component is NaN");
    expect_refused(header + "1 0 0\n0 -inf 0\n0 0 1\n", "bad.axes:4: axis component is infinite");
    expect_refused(header + "1 0 0\n0 1 0\n0 0 1\n0 2 0\n", "bad.axes:6: axis duplicates the axis on line 4");
    expect_refused(header + "1 0 0\n0 1 0\n0 0 1\n-1 0 0\n", "bad.axes:6: axis is antiparallel to the axis on line 3");
    expect_refused(header + "1 0 0\n0 1 0\n1 1 0\n", "bad.axes: the 3 axes do not span 3-D space");
}

TEST(Cli, GenRefusesUnknownNamesAndBadOptionsAndWritesNothing) {
    test::TempDir dir;
    fs::path out = dir / "out";
    struct Case {
        std::string args, message;
    };
    const Case cases[] = {
        {"--sets dop99", "--sets: 'dop99' is not a built-in axis set"},
        {"--modes clamp", "--modes: unknown mode 'clamp' (expected clip or varclip)"},
        {"--neighborhoods n25", "--neighborhoods: unknown neighborhood 'n25' (expected n9 or n5)"},
        {"--sets aabb aabb", "--sets: 'aabb' is given twice"},
        {"--threads many", "--threads"},
        {"--frobnicate", "--frobnicate"},
    };
    for (const Case& c : cases) {
        auto r = run(kdop("gen --out " + out.string() + " " + c.args));
        EXPECT_NE(r.exit_code, 0) << c.args;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": stderr was: " << r.err;
        EXPECT_FALSE(fs::exists(out)) << c.args;
    }
    auto r = run(kdop("gen"));
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("--out is required"), std::string::npos) << r.err;
}

TEST(Cli, ShowPrintsTheFunctionOrTheComputeShader) {
    auto r = run(kdop("show dop32-clip-n9"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("vec3 kdop_dop32_clip_n9(vec3 current, vec3 history, vec3 neighborhood[9])"),
              std::string::npos);
    EXPECT_EQ(r.out.find("void main()"), std::string::npos);

    r = run(kdop("show dop22-varclip-n5 --compute"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("void main()"), std::string::npos);
    EXPECT_NE(r.out.find("float gamma;"), std::string::npos);

    r = run(kdop("show dop22-varclip-n9-loop"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("[[unroll]] for (int a = 0; a < 11; ++a)"), std::string::npos);

    r = run(kdop("show dop32-varclip-n9 --hlsl"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("float3 kdop_dop32_varclip_n9(float3 current, float3 history, float gamma, float3 "
                         "neighborhood[9])"),
              std::string::npos);
    r = run(kdop("show dop32-varclip-n9 --wgsl"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("fn kdop_dop32_varclip_n9(current: vec3f, history: vec3f, gamma: f32, neighborhood: "
                         "array<vec3f, 9>) -> vec3f"),
              std::string::npos);
    r = run(kdop("show dop32-clip-n9 --wgsl --hlsl"));
    EXPECT_EQ(r.exit_code, 2) << "one language at a time";
    r = run(kdop("show dop32-clip-n9 --wgsl --compute"));
    EXPECT_EQ(r.exit_code, 2) << "kdop has no WGSL compute shader";
    r = run(kdop("show dop22-varclip-n5 --compute --hlsl"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("[numthreads(8, 8, 1)]"), std::string::npos);
    EXPECT_NE(r.out.find("[[vk::push_constant]] ConstantBuffer<Parameters> parameters;"), std::string::npos);

    r = run(kdop("show tiny-clip-n9 --sets " + test::data_path("tiny.axes")));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("kdop_tiny_clip_n9"), std::string::npos);

    r = run(kdop("show dop32-clamp-n9"));
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("show: 'dop32-clamp-n9' is not a variant name"), std::string::npos) << r.err;
    r = run(kdop("show tiny-clip-n9"));
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("show: no axis set is named 'tiny'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--sets FILE"), std::string::npos) << r.err;
    // Paper twins are shown like any other variant, by name or with --numerics.
    r = run(kdop("show dop32-clip-n9 --numerics paper"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, run(kdop("show dop32-clip-n9-paper")).out);
    EXPECT_NE(r.out, run(kdop("show dop32-clip-n9")).out);
}

TEST(Cli, EverySubcommandHasHelp) {
    for (std::string sub : {"", "list ", "gen ", "show ", "run ", "textures ", "bench ", "stress ", "accuracy ",
                            "optimize ", "flip ", "taa "}) {
        auto r = run(kdop(sub + "--help"));
        EXPECT_EQ(r.exit_code, 0) << sub;
        EXPECT_NE(r.out.find("Usage"), std::string::npos) << sub << r.out;
    }
    auto r = run(kdop(""));
    EXPECT_NE(r.exit_code, 0);
}

TEST(Cli, VersionNamesTheProgramAndItsVersion) {
    auto r = run(kdop("--version"));
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.out, std::string("kdop ") + KDOP_VERSION + "\n");
    r = run(test::kdop_gen_binary() + " --version");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.out, std::string("kdop-gen ") + KDOP_VERSION + "\n");
}

// Exit statuses a script can rely on: 0 done, 1 failed (with a message), 2 the command line is wrong.
TEST(Cli, ExitStatusSaysUsageErrorsApartFromFailures) {
    EXPECT_EQ(run(kdop("list --no-such-option")).exit_code, 2);
    EXPECT_EQ(run(kdop("run --variant aabb-clip-n9")).exit_code, 2); // --current and others missing
    EXPECT_EQ(run(kdop("bench --out x --repeat 0")).exit_code, 2);
    EXPECT_EQ(run(test::kdop_gen_binary() + " glsl").exit_code, 2);
    EXPECT_EQ(run(kdop("show dop99-clip-n9")).exit_code, 2); // no such set: the command line names it
    EXPECT_EQ(run(kdop("show dop22-clip-n9 --sets /no/such/file.axes")).exit_code, 1); // a file that cannot be read
    EXPECT_EQ(run(kdop("list --help")).exit_code, 0);
}

} // namespace
} // namespace kdop

namespace kdop {
namespace {

// A 16x16 current frame, a history of the same size, one of another size, and a text file.
struct RunInputs {
    test::TempDir dir;
    std::string current = (dir / "current.exr").string(), history = (dir / "history.exr").string(),
                small = (dir / "small.exr").string(), text = (dir / "notes.exr").string(),
                out = (dir / "out.exr").string();
    RunInputs() {
        Image c(16, 16), h(16, 16, {2.0f, 0.0f, 0.5f, 1.0f}), s(8, 8);
        for (std::uint32_t i = 0; i < c.pixels.size(); ++i)
            c.pixels[i] = glm::vec4(0.1f * (i % 7), 0.05f * (i % 5), 0.3f, 1);
        EXPECT_TRUE(write_image(current, c));
        EXPECT_TRUE(write_image(history, h));
        EXPECT_TRUE(write_image(small, s));
        test::write_file(text, "not an image");
    }
    std::string args(const std::string& variant, const std::string& extra = "") const {
        return "run --variant " + variant + " --current " + current + " --history " + history + " --out " + out + " " +
               extra;
    }
};

TEST(CliRun, WritesTheRectifiedHistory) {
    RunInputs in;
    auto r = run(kdop(in.args("dop32-clip-n9")));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("dop32-clip-n9 on llvmpipe"), std::string::npos) << r.out;
    auto out = read_image(in.out);
    ASSERT_TRUE(out) << out.error().message;
    auto current = read_image(in.current);
    // The history (2, 0, 0.5) lies far outside every neighborhood here: it must have moved.
    EXPECT_LT(out->at(5, 5).r, 1.0f);
    EXPECT_GE(out->at(5, 5).r, current->at(5, 5).r - 1e-4f);
    EXPECT_EQ(run(kdop(in.args("dop22-varclip-n5", "--gamma 0.5 --format rgba16f"))).exit_code, 0);
}

// Every variant runs, not only the embedded ones: a user's set (built in-process) and a paper twin
// each give what the double-precision reference computes for them.
TEST(CliRun, RunsAUserSetAndPaperNumericsAsTheReferenceComputesThem) {
    RunInputs in;
    const auto current = read_image(in.current), history = read_image(in.history);
    ASSERT_TRUE(current && history);
    struct Case {
        std::string args;
        VariantSpec spec;
    };
    const Case cases[] = {
        {in.args("tiny-clip-n9", "--sets " + test::data_path("tiny.axes")),
         {*resolve_axis_set(test::data_path("tiny.axes")), Mode::clip, Neighborhood::n9}},
        {in.args("dop32-clip-n5", "--numerics paper"), {*resolve_axis_set("dop32"), Mode::clip, Neighborhood::n5}},
    };
    for (const Case& c : cases) {
        auto r = run(kdop(c.args));
        ASSERT_EQ(r.exit_code, 0) << c.args << "\n" << r.err;
        auto out = read_image(in.out);
        ASSERT_TRUE(out) << out.error().message;
        const Image reference =
            reference_rectify(c.spec.set, c.spec.mode, c.spec.neighborhood, *current, *history, 1.0);
        for (std::size_t i = 0; i < out->pixels.size(); ++i)
            ASSERT_NEAR(glm::distance(glm::vec3(out->pixels[i]), glm::vec3(reference.pixels[i])), 0.0, 1e-5)
                << c.args << " at pixel " << i;
    }
    EXPECT_NE(run(kdop(in.args("dop32-clip-n9", "--numerics paper"))).out.find("dop32-clip-n9-paper on "),
              std::string::npos);
}

// Several runs at once, to one output and to outputs of their own: each writes under a temporary
// name of its own and renames it into place, so every run succeeds and every file is whole.
TEST(CliRun, ConcurrentRunsToTheSameAndToOtherOutputsAllSucceed) {
    RunInputs in;
    const fs::path dir = in.dir.path();
    std::string script;
    for (int i = 0; i < 4; ++i) {
        const std::string same = "run --variant dop22-clip-n9 --current " + in.current + " --history " + in.history +
                                 " --out " + (dir / "same.exr").string();
        const std::string own = "run --variant dop22-clip-n9 --current " + in.current + " --history " + in.history +
                                " --out " + (dir / ("own" + std::to_string(i) + ".exr")).string();
        script += fmt::format("({} > /dev/null 2>&1; echo $? > {}/same{}.rc) & ", kdop(same), dir.string(), i);
        script += fmt::format("({} > /dev/null 2>&1; echo $? > {}/own{}.rc) & ", kdop(own), dir.string(), i);
    }
    ASSERT_EQ(run(script + "wait").exit_code, 0);
    const std::string expected = test::read_file(dir / "own0.exr");
    ASSERT_FALSE(expected.empty());
    for (int i = 0; i < 4; ++i) {
        for (const char* kind : {"same", "own"})
            EXPECT_EQ(test::read_file(dir / fmt::format("{}{}.rc", kind, i)), "0\n") << kind << i;
        EXPECT_EQ(test::read_file(dir / ("own" + std::to_string(i) + ".exr")), expected) << i;
    }
    EXPECT_EQ(test::read_file(dir / "same.exr"), expected) << "the same bytes, whichever run renamed last";
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_EQ(entry.path().string().find("kdop-partial"), std::string::npos) << entry.path();
}

TEST(CliRun, RefusesBadInputAndWritesNothing) {
    RunInputs in;
    struct Case {
        std::string args, message;
    };
    const Case cases[] = {
        {in.args("dop99-clip-n9"), "--variant: no axis set is named 'dop99'"},
        {in.args("dop32-clamp-n9"), "--variant: 'dop32-clamp-n9' is not a variant name"},
        {in.args("dop32-clip-n9-paper", "--numerics hardened"),
         "--numerics: hardened conflicts with the variant's own -paper"},
        {in.args("dop32-clip-n9", "--gamma 1"), "--gamma: dop32-clip-n9 is not a variance clip and takes no gamma"},
        {in.args("dop32-varclip-n9", "--gamma -1"), "--gamma: '-1' is not a number above 0 and at most 100"},
        {in.args("dop32-varclip-n9", "--gamma nan"), "--gamma"},
        {in.args("dop32-clip-n9", "--format rgb8"), "--format: 'rgb8' is not rgba32f or rgba16f"},
        {"run --variant aabb-clip-n9 --current " + in.current + " --history " + in.small + " --out " + in.out,
         "is 8x8 but --current"},
        {"run --variant aabb-clip-n9 --current " + in.text + " --history " + in.history + " --out " + in.out,
         in.text + ": cannot read image"},
        {"run --variant aabb-clip-n9 --current " + in.current + " --history /nonexistent.exr --out " + in.out,
         "/nonexistent.exr: cannot read image"},
        {"run --variant aabb-clip-n9 --current " + in.current + " --history " + in.history + " --out " + in.out +
             ".xyz",
         "--out: " + in.out + ".xyz: no image format for this extension"},
        {in.args("aabb-clip-n9", "--device NoSuchGpu"), "no Vulkan device whose name contains 'NoSuchGpu'"},
        // 65-byte files whose headers claim what no device or memory holds: refused from the header.
        {"run --variant aabb-clip-n9 --current " + test::data_path("huge-1000000x1000000.png") + " --history " +
             in.history + " --out " + in.out,
         "huge-1000000x1000000.png: 1000000x1000000 is larger than the device allows: at most"},
        {"run --variant aabb-clip-n9 --current " + test::data_path("wide-100000x1.png") + " --history " + in.history +
             " --out " + in.out,
         "wide-100000x1.png: 100000x1 is larger than the device allows"},
    };
    for (const Case& c : cases) {
        auto r = run(kdop(c.args));
        EXPECT_NE(r.exit_code, 0) << c.args;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\nstderr was: " << r.err;
        EXPECT_FALSE(fs::exists(in.out)) << c.args;
    }
    size_t leftovers = 0;
    for (const auto& entry : fs::directory_iterator(in.dir.path()))
        leftovers += entry.path().string().find("partial") != std::string::npos;
    EXPECT_EQ(leftovers, 0u);
}

TEST(CliTextures, WritesEveryTextureAndHistoryAndReportsTheSeed) {
    test::TempDir dir;
    auto r = run(kdop("textures --no-real --width 32 --height 24 --seed 5 --out " + (dir / "t").string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("seed 5"), std::string::npos);
    for (std::string family : {"grass", "asphalt", "edges", "gradient", "flat", "hdr"}) {
        auto image = read_image((dir / "t" / (family + ".exr")).string());
        ASSERT_TRUE(image) << family;
        EXPECT_EQ(image->width, 32u);
        EXPECT_EQ(image->height, 24u);
        for (std::string model : {"same", "shifted", "moved-object", "other-texture"})
            EXPECT_TRUE(fs::exists(dir / "t" / (family + "-history-" + model + ".exr"))) << family << " " << model;
    }
    // Same seed, same bytes, also a second later (no time stamp in the files).
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    ASSERT_EQ(run(kdop("textures --no-real --width 32 --height 24 --seed 5 --out " + (dir / "u").string())).exit_code,
              0);
    EXPECT_EQ(test::read_file(dir / "t" / "grass.exr"), test::read_file(dir / "u" / "grass.exr"));
    EXPECT_NE(run(kdop("textures --width 3 --out " + (dir / "v").string())).exit_code, 0);
}

// Errors, never an abort: an unwritable folder and a size whose images cannot fit in memory are
// refused before anything is made, with a message and exit status 1.
TEST(CliTextures, RefusesWhatItCannotWriteOrHoldAndNeverAborts) {
    test::TempDir dir;
    auto r = run(kdop("textures --out /proc/kdop-textures"));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("--out: /proc/kdop-textures: cannot create files in /proc"), std::string::npos) << r.err;
    r = run(kdop("textures --width 16384 --height 16384 --out " + (dir / "t").string()));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("--width 16384 --height 16384: needs about 192.0 GiB of memory"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "t"));
}

} // namespace
} // namespace kdop

namespace kdop {
namespace {

TEST(CliStress, PrintsTheTableWritesItsFilesAndExitsByTheResult) {
    test::TempDir dir;
    const std::string out = (dir / "stress").string();
    auto r = run(kdop("stress --sets aabb --modes clip --neighborhoods n5 --seed 3 --out " + out));
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    EXPECT_NE(r.out.find("aabb-clip-n5 "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("All 18 variant-case pairs kept every invariant."), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("seed 3"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("[18/18] stress on "), std::string::npos) << "progress on stderr: " << r.err;
    EXPECT_EQ(lines(test::read_file(out + "/stress.csv")).size(), 1u + 18u);
    EXPECT_NE(test::read_file(out + "/stress.json").find("\"seed\": 3"), std::string::npos);
    EXPECT_NE(test::read_file(out + "/report.md").find("| aabb-clip-n5 | ok |"), std::string::npos);
    // The paper's numerics break invariants: the table says which, and the exit status is 3.
    auto paper = run(kdop("stress --sets aabb --modes clip --neighborhoods n5 --numerics paper"));
    EXPECT_EQ(paper.exit_code, 3) << paper.err;
    EXPECT_NE(paper.out.find("aabb-clip-n5-paper"), std::string::npos) << paper.out;
    EXPECT_NE(paper.out.find(" ND "), std::string::npos) << paper.out;
}

TEST(CliStress, RefusesBadInputAndWritesNothing) {
    test::TempDir dir;
    const std::string out = (dir / "stress").string();
    struct Case {
        std::string args, message;
    };
    const Case cases[] = {
        {"--gamma -1", "--gamma: '-1' is not a number above 0 and at most 100"},
        {"--baselines", "--baselines: the gather and copy baselines are not clips"},
        {"--sets dop99", "--sets: 'dop99' is not a built-in axis set"},
        {"--numerics exact", "--numerics"},
        {"--device NoSuchGpu", "no Vulkan device whose name contains 'NoSuchGpu'"},
    };
    for (const Case& c : cases) {
        auto r = run(kdop("stress --sets aabb --modes clip --neighborhoods n5 --out " + out + " " + c.args));
        EXPECT_NE(r.exit_code, 0) << c.args;
        EXPECT_NE(r.exit_code, 3) << c.args << ": bad input is not a broken invariant";
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\nstderr was: " << r.err;
        EXPECT_FALSE(fs::exists(out)) << c.args;
    }
}

} // namespace
} // namespace kdop

namespace kdop {
namespace {

// 3x3 pixels: a black left column, white elsewhere; the history red everywhere. With 3x3
// neighborhoods (clamped), the left two columns see black and white, the gray diagonal: red is
// off that line, so the ideal keeps the current color (t* = 0). The RGB AABB is the unit cube and
// keeps red: a distance of |red - black| = 1 in the left column and |red - white| = sqrt 2 in the
// middle. The right column sees only white: the AABB is a padded point and clips at once.
struct AccuracyInputs {
    test::TempDir dir;
    std::string current = (dir / "current.exr").string(), history = (dir / "history.exr").string(),
                small = (dir / "small.exr").string(), nan = (dir / "nan.exr").string(), out = (dir / "out").string();
    AccuracyInputs() {
        Image c(3, 3, {1, 1, 1, 1}), h(3, 3, {1, 0, 0, 1}), n(3, 3, {1, 1, 1, 1});
        for (std::uint32_t y = 0; y < 3; ++y) c.at(0, y) = {0, 0, 0, 1};
        n.at(2, 1) = {0, NAN, 0, 1};
        EXPECT_TRUE(write_image(current, c));
        EXPECT_TRUE(write_image(history, h));
        EXPECT_TRUE(write_image(small, Image(2, 2)));
        EXPECT_TRUE(write_image(nan, n));
    }
};

TEST(CliAccuracy, MeasuresATinyPairAsWorkedOutByHand) {
    AccuracyInputs in;
    auto r = run(kdop("accuracy --sets aabb --modes clip --neighborhoods n9 --volume-samples 0 --current " +
                      in.current + " --history " + in.history + " --out " + in.out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("current: ideal clip n9"), std::string::npos) << "progress on stderr: " << r.err;
    const auto csv = lines(test::read_file(in.out + "/accuracy.csv"));
    ASSERT_EQ(csv.size(), 2u);
    std::vector<std::string> header, values;
    for (auto [line, into] : {std::pair{&csv[0], &header}, std::pair{&csv[1], &values}}) {
        std::stringstream fields(*line);
        for (std::string f; std::getline(fields, f, ',');) into->push_back(f);
    }
    ASSERT_EQ(header.size(), values.size());
    auto value = [&](const std::string& column) {
        const auto at = std::find(header.begin(), header.end(), column);
        EXPECT_NE(at, header.end()) << column;
        return at == header.end() ? NAN : std::stod(values[at - header.begin()]);
    };
    EXPECT_EQ(values[0], "aabb-clip-n9");
    EXPECT_NEAR(value("mean_dist"), (3 * 1 + 3 * std::sqrt(2.0)) / 9, 1e-4); // the right column: about 1e-5
    EXPECT_NEAR(value("p95_dist"), std::sqrt(2.0), 1e-6);
    EXPECT_NEAR(value("max_dist"), std::sqrt(2.0), 1e-6);
    EXPECT_DOUBLE_EQ(value("outside_hull_rate"), 1.0);
    EXPECT_NEAR(value("false_accept_rate"), 6.0 / 9.0, 1e-6);
    EXPECT_NEAR(value("ref_mean_dist"), value("mean_dist"), 1e-6);
    for (const char* file : {"trade.csv", "report.md", "pareto-current.png", "accuracy.json", "trade.json"})
        EXPECT_TRUE(fs::exists(in.out + "/" + file)) << file;
}

// Charts are optional: without gnuplot (an empty PATH here) the run warns and still writes its
// tables and its report, which then shows no chart.
TEST(CliAccuracy, WithoutGnuplotWritesEverythingButTheCharts) {
    AccuracyInputs in;
    auto r = run("PATH=/nonexistent " + kdop("accuracy --sets aabb --modes clip --neighborhoods n9 --volume-samples 0 "
                                             "--current " +
                                             in.current + " --history " + in.history + " --out " + in.out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: gnuplot not found"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(in.out + "/accuracy.csv"));
    EXPECT_FALSE(fs::exists(in.out + "/pareto-current.png"));
    EXPECT_EQ(test::read_file(in.out + "/report.md").find("!["), std::string::npos);
}

TEST(CliAccuracy, RefusesBadInputAndWritesNothing) {
    AccuracyInputs in;
    test::write_file(in.dir / "cost.csv", "variant,k\n");
    struct Case {
        std::string args, message;
    };
    const std::string pair = " --current " + in.current + " --history " + in.history;
    const Case cases[] = {
        {"--current " + in.current, "--current requires --history"},
        {"--images " + in.current + pair, "excludes --images"},
        {"--current " + in.current + " --history " + in.small, "is 2x2 but --current"},
        {"--current " + in.nan + " --history " + in.history, in.nan + ": pixel (2, 1) is not finite"},
        {"--images " + (in.dir / "missing.exr").string(), "missing.exr: cannot read image"},
        {"--size 16" + pair, "--size: only for the built-in content"},
        {"--gamma -1" + pair, "--gamma: '-1' is not a number above 0 and at most 100"},
        {"--baselines" + pair, "--baselines: the gather and copy baselines are not clips"},
        {"--cost " + (in.dir / "cost.csv").string() + pair, "cost.csv:1: not a kdop bench cost.csv"},
        {"--cost " + (in.dir / "none.csv").string() + pair, "none.csv: cannot read"},
        {"--sets dop99" + pair, "--sets: 'dop99' is not a built-in axis set"},
        {"--images " + test::data_path("huge-1000000x1000000.png"), "a 1000000x1000000 image: needs about"},
    };
    for (const Case& c : cases) {
        auto r = run(kdop("accuracy --sets aabb --modes clip --neighborhoods n5 --out " + in.out + " " + c.args));
        EXPECT_NE(r.exit_code, 0) << c.args;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\nstderr was: " << r.err;
        EXPECT_FALSE(fs::exists(in.out)) << c.args;
    }
    // A bad --out is found before the work: no progress line was printed.
    auto r = run(kdop("accuracy --sets aabb --modes clip --neighborhoods n5 --out /proc/kdop-accuracy"));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("--out: /proc/kdop-accuracy: cannot create files in /proc"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("ideal clip"), std::string::npos) << r.err;
}

} // namespace
} // namespace kdop
