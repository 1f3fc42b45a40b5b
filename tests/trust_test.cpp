// What a user must be able to trust without reading the code (issue "trust by default"): no output
// replaces an input, a failed or interrupted run leaves the previous outputs as they were, an input
// given twice is refused however it is spelled, inputs that are not files cannot hang kdop, and
// every bad command line is refused before the work, with exit 2.
#include "core/input_files.h"
#include "core/write_files.h"

#include "generator/variant_spec.h"
#include "images/image_io.h"
#include "images/texture_cases.h"
#include "reference/cpu_clip.h"
#include "tests/interrupt_support.h"
#include "tests/test_support.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <csignal>

namespace kdop {
namespace {
namespace fs = std::filesystem;

using test::has_temporaries;
using test::snapshot;

std::string kdop(const std::string& args) { return test::kdop_binary() + " " + args; }

// ---------------------------------------------------------------------------------------------
// The output set (core/write_files.h)

TEST(WriteSet, AFailedMovePutsThePreviousFilesBack) {
    test::TempDir dir;
    const fs::path a = dir / "out" / "a.csv", b = dir / "out" / "b.csv", late = dir / "out" / "late.csv";
    ASSERT_TRUE(write_files_atomically({{a, "old a"}, {b, "old b"}}));
    const OutputFile new_a{a, "new a"}, new_b{b, "new b"}, new_late{late, "new"};
    // The last file's destination becomes a folder with a file in it while the set is written (as
    // another process could make it), so its move fails after a and b have been replaced.
    OutputWriter sabotaged = content_writer(new_late);
    sabotaged.write = [&, inner = sabotaged.write](const fs::path& temporary) {
        fs::create_directories(late / "inside");
        return inner(temporary);
    };
    auto failed = write_atomically({content_writer(new_a), content_writer(new_b), sabotaged});
    ASSERT_FALSE(failed);
    EXPECT_NE(failed.error().message.find("late.csv: cannot move into place: it has become a directory"),
              std::string::npos)
        << failed.error().message;
    EXPECT_EQ(test::read_file(a), "old a") << "a replaced file is put back";
    EXPECT_EQ(test::read_file(b), "old b");
    EXPECT_TRUE(fs::exists(late / "inside")) << "what is not the set's stays";
    EXPECT_FALSE(has_temporaries(dir.path()));
}

TEST(WriteSet, AFolderOrAnInputAsADestinationIsRefusedBeforeAnythingIsWritten) {
    test::TempDir dir;
    const fs::path a = dir / "a.csv", folder = dir / "b.csv";
    ASSERT_TRUE(write_files_atomically({{a, "old a"}}));
    fs::create_directory(folder);
    auto refused = write_files_atomically({{a, "new a"}, {folder, "b"}});
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("b.csv: is a directory"), std::string::npos) << refused.error().message;
    EXPECT_EQ(test::read_file(a), "old a");

    // An input, spelled another way, through a link.
    test::write_file(dir / "input.exr", "pixels");
    protect_inputs();
    note_input(dir / "input.exr");
    fs::create_symlink(dir / "input.exr", dir / "link.exr");
    for (const fs::path& output : {dir / "input.exr", dir / "." / "input.exr", dir / "link.exr"}) {
        auto over_input = write_files_atomically({{output, "not pixels"}});
        ASSERT_FALSE(over_input) << output;
        EXPECT_NE(over_input.error().message.find("is an input of this run"), std::string::npos)
            << over_input.error().message;
    }
    protect_inputs(false);
    EXPECT_EQ(test::read_file(dir / "input.exr"), "pixels");
    EXPECT_FALSE(has_temporaries(dir.path()));
}

TEST(WriteSet, FilesAreComparedByWhatTheyAreNotHowTheyAreSpelled) {
    test::TempDir dir;
    test::write_file(dir / "a.exr", "a");
    fs::create_hard_link(dir / "a.exr", dir / "hard.exr");
    fs::create_directory(dir / "sub");
    EXPECT_TRUE(same_file(dir / "a.exr", dir / "sub" / ".." / "a.exr"));
    EXPECT_TRUE(same_file(dir / "a.exr", dir / "hard.exr"));
    EXPECT_FALSE(same_file(dir / "a.exr", dir / "missing.exr"));
    const std::vector<std::string> twice{(dir / "a.exr").string(), (dir / "hard.exr").string()};
    auto refused = check_distinct_files(twice, "--images");
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("hard.exr is given twice (as "), std::string::npos)
        << refused.error().message;
    const fs::path inputs[] = {dir / "a.exr"};
    EXPECT_FALSE(check_not_an_input(dir / "hard.exr", "--out", inputs));
    EXPECT_TRUE(check_not_an_input(dir / "b.exr", "--out", inputs));
}

// ---------------------------------------------------------------------------------------------
// Interrupted runs (core/interrupt.h)

using test::interrupt_at_write;

TEST(CliInterrupt, SigtermWhileGenWritesLeavesTheFolderAsItWas) {
    test::TempDir dir;
    const fs::path out = dir / "variants";
    ASSERT_EQ(test::run(kdop("gen --sets dop22 --modes clip --neighborhoods n9 n5 --out " + out.string())).exit_code,
              0);
    const auto before = snapshot(out);
    ASSERT_EQ(before.size(), 11u); // dop22-clip-n9 and -n5: .glsl .hlsl .wgsl .comp .spv; variants.json
    auto ended = interrupt_at_write(kdop("gen --sets dop22 --out " + out.string() + " --forms unrolled loop"), SIGTERM);
    EXPECT_EQ(ended.exit_code, 143) << ended.err;
    EXPECT_NE(ended.err.find("kdop: interrupted"), std::string::npos) << ended.err;
    EXPECT_EQ(snapshot(out), before);
    EXPECT_FALSE(has_temporaries(dir.path()));
}

TEST(CliInterrupt, SigintWhileTaaWritesLeavesNothingBehind) {
    test::TempDir dir;
    const fs::path out = dir / "taa" / "deeper";
    auto ended = interrupt_at_write(kdop("taa --size 64x36 --warmup 2 --frames 1 --timing-rounds 1 --sets aabb "
                                         "--modes clip --scenes grass --out " +
                                         out.string()),
                                    SIGINT);
    EXPECT_EQ(ended.exit_code, 130) << ended.err;
    EXPECT_FALSE(fs::exists(dir / "taa")) << "the folders made for the outputs go too";
}

// Interrupted in the middle of the pass over a sequence's frames (the next one being read ahead on
// a worker, every measured output staged for --write-frames): nothing is left, the staged frames'
// scratch folder included.
TEST(CliInterrupt, SigintDuringTheFramesLeavesNothingBehind) {
    test::TempDir dir;
    fs::create_directory(dir / "tmp");
    ASSERT_EQ(test::run(kdop("scene --scenes grass --size 48x32 --frames 8 --out " + (dir / "seq").string())).exit_code,
              0);
    auto ended = interrupt_at_write(kdop("taa --sequence " + (dir / "seq" / "grass-ghosting").string() +
                                         " --warmup 2 --timing-rounds 1 --sets aabb dop32 --modes clip "
                                         "--write-frames --no-charts --out " +
                                         (dir / "taa").string()),
                                    SIGINT, "TMPDIR=" + (dir / "tmp").string(), "taa_pass");
    EXPECT_EQ(ended.exit_code, 130) << ended.err;
    EXPECT_NE(ended.err.find("taa_pass: holding"), std::string::npos) << ended.err;
    EXPECT_FALSE(fs::exists(dir / "taa"));
    EXPECT_TRUE(fs::is_empty(dir / "tmp")) << "kdop-frames-* is removed";
}

// A crash (a driver's segmentation fault, an abort in a library) runs the same undo steps: the
// staged frames' scratch folder and the temporaries go, then the signal ends the process.
TEST(CliInterrupt, ACrashLeavesNoScratchFolderNorTemporary) {
    test::TempDir dir;
    fs::create_directory(dir / "tmp");
    for (int crash : {SIGSEGV, SIGABRT}) {
        auto ended = interrupt_at_write(kdop("taa --size 64x36 --warmup 2 --frames 1 --timing-rounds 1 --sets aabb "
                                             "--modes clip --scenes grass --write-frames --no-charts --out " +
                                             (dir / "taa").string()),
                                        crash, "TMPDIR=" + (dir / "tmp").string());
        EXPECT_EQ(ended.exit_code, -1) << "ended by the signal: " << ended.err;
        EXPECT_TRUE(fs::is_empty(dir / "tmp")) << "kdop-frames-* is removed";
        EXPECT_FALSE(fs::exists(dir / "taa"));
    }
}

TEST(CliInterrupt, AnInterruptedBenchRemovesItsScratchFolder) {
    test::TempDir dir;
    fs::create_directory(dir / "tmp");
    auto ended = interrupt_at_write(kdop("bench --variants aabb-clip-n9 --size 16x16 --repeat 1 --no-sweep "
                                         "--callgrind-size 8 --no-charts --out " +
                                         (dir / "bench").string()),
                                    SIGTERM, "TMPDIR=" + (dir / "tmp").string());
    EXPECT_EQ(ended.exit_code, 143) << ended.err;
    EXPECT_TRUE(fs::is_empty(dir / "tmp")) << "scratch folders (callgrind's files) are removed";
    EXPECT_FALSE(fs::exists(dir / "bench"));
}

// ---------------------------------------------------------------------------------------------
// Commands

struct TrustRun {
    test::TempDir dir;
    std::string grass, asphalt; // 24x24 textures
    TrustRun() {
        grass = (dir / "grass.exr").string();
        asphalt = (dir / "asphalt.exr").string();
        EXPECT_TRUE(write_image(grass, make_texture(TextureFamily::grass, 24, 24, 1)));
        EXPECT_TRUE(write_image(asphalt, make_texture(TextureFamily::asphalt, 24, 24, 2)));
    }
    static constexpr const char* kQuickFit = " --axes 4 --starts 1 --iterations 2 --accuracy-samples 0";
};

TEST(CliTrust, NoOutputReplacesAnInputHoweverItIsSpelled) {
    TrustRun t;
    const std::string bytes = test::read_file(t.grass);
    fs::create_symlink(t.grass, t.dir / "link.exr");
    fs::create_hard_link(t.grass, t.dir / "hard.exr");
    fs::create_directory(t.dir / "sub");
    for (const fs::path& out :
         {fs::path(t.grass), t.dir / "sub" / ".." / "grass.exr", t.dir / "link.exr", t.dir / "hard.exr"}) {
        auto r = test::run(
            kdop("optimize --images " + t.grass + TrustRun::kQuickFit + " --name fitted --out " + out.string()));
        EXPECT_EQ(r.exit_code, 2) << out;
        EXPECT_NE(r.err.find("is an input of this run"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("fitting"), std::string::npos) << "refused before the fit: " << r.err;
    }
    auto flip = test::run(kdop("flip --reference " + t.grass + " --test " + t.asphalt + " --out " + t.grass));
    EXPECT_EQ(flip.exit_code, 2) << "the command line named both";
    EXPECT_NE(flip.err.find("--out " + t.grass + ": is an input of this run"), std::string::npos) << flip.err;
    EXPECT_EQ(test::read_file(t.grass), bytes);
}

TEST(CliTrust, ARunThatCannotWriteLeavesThePreviousRunWhole) {
    TrustRun t;
    const fs::path out = t.dir / "taa";
    const std::string command =
        kdop("taa --size 64x36 --warmup 2 --frames 1 --timing-rounds 1 --sets aabb --modes clip --scenes grass "
             "--out " +
             out.string());
    ASSERT_EQ(test::run(command).exit_code, 0);
    fs::remove(out / "frames" / "grass" / "aliased.png");
    fs::create_directories(out / "frames" / "grass" / "aliased.png" / "in the way");
    const auto before = snapshot(out);
    auto r = test::run(command);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("aliased.png: is a directory"), std::string::npos) << r.err;
    EXPECT_EQ(snapshot(out), before) << "taa.csv, taa.json, report.md and the frames of the first run stay";
    EXPECT_FALSE(has_temporaries(out));
}

TEST(CliTrust, AnInputGivenTwiceIsRefusedHoweverItIsSpelled) {
    TrustRun t;
    fs::create_directory(t.dir / "sub");
    const std::string again = (t.dir / "sub" / ".." / "grass.exr").string();
    auto fit = test::run(kdop("optimize --images " + t.grass + " " + again + TrustRun::kQuickFit + " --out " +
                              (t.dir / "fitted.axes").string()));
    EXPECT_EQ(fit.exit_code, 1);
    EXPECT_NE(fit.err.find("--images: " + again + " is given twice (as " + t.grass + " too)"), std::string::npos)
        << fit.err;
    auto accuracy =
        test::run(kdop("accuracy --sets aabb --images " + t.grass + " " + again + " --out " + (t.dir / "a").string()));
    EXPECT_EQ(accuracy.exit_code, 1);
    EXPECT_NE(accuracy.err.find("is given twice"), std::string::npos) << accuracy.err;
    auto taa = test::run(kdop("taa --scenes grass grass --out " + (t.dir / "taa").string()));
    EXPECT_EQ(taa.exit_code, 2);
    EXPECT_NE(taa.err.find("--scenes: 'grass' is given twice"), std::string::npos) << taa.err;
    EXPECT_FALSE(fs::exists(t.dir / "fitted.axes"));
    EXPECT_FALSE(fs::exists(t.dir / "a"));
}

TEST(CliTrust, AFlatImageHasNothingToFit) {
    TrustRun t;
    const std::string flat = (t.dir / "flat.exr").string();
    ASSERT_TRUE(write_image(flat, Image(16, 16, {0.25f, 0.5f, 0.125f, 1})));
    auto r = test::run(
        kdop("optimize --images " + flat + TrustRun::kQuickFit + " --out " + (t.dir / "fitted.axes").string()));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find(flat + ": every pixel is (0.25, 0.5, 0.125)"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(t.dir / "fitted.axes"));
}

TEST(CliTrust, InputsThatAreNotFilesAreRefusedAtOnce) {
    TrustRun t;
    struct Case {
        std::string args, message;
    };
    const Case cases[] = {
        {"list --manifest /dev/zero", "/dev/zero: is not a regular file"},
        {"list --manifest " + t.dir.path().string(), "is a directory, not a file (the manifest)"},
        {"optimize --images /dev/zero --axes 4 --out " + (t.dir / "x.axes").string(), "/dev/zero: cannot read image"},
        {"flip --reference /dev/zero --test " + t.grass, "/dev/zero: cannot read image: is not a regular file"},
    };
    for (const Case& c : cases) {
        // `timeout`: before the fix these read /dev/zero without end.
        auto r = test::run("timeout 60 " + kdop(c.args));
        EXPECT_EQ(r.exit_code, 1) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
    }
}

TEST(CliTrust, EveryBadCommandLineIsRefusedBeforeTheWorkWithExit2) {
    TrustRun t;
    fs::create_directory(t.dir / "folder");
    fs::create_directory(t.dir / "folder.exr");
    const std::string fit = "optimize --images " + t.grass + TrustRun::kQuickFit;
    const std::string out = " --out " + (t.dir / "fitted.axes").string();
    struct Case {
        std::string args, message;
    };
    const Case cases[] = {
        {"optimize --sphere --axes 4 --time-limit 1e10" + out, "--time-limit: '1e10' is not a number above 0"},
        {"optimize --sphere --axes 4 --time-limit nan" + out, "--time-limit: 'nan' is not a number"},
        {"optimize --sphere --axes 4 --time-limit inf" + out, "--time-limit: 'inf' is not a number"},
        {"optimize --sphere --axes 4 --target nan" + out, "--target: 'nan' is not a number"},
        {fit + " --out " + (t.dir / "folder").string(), "is a directory; name the axis-set file"},
        {fit + " --max-nonzero 3" + out, "--max-nonzero 3: each of the 4 axes keeps at least one component"},
        {fit + " --name dop32" + out, "--name: 'dop32' is the name of a built-in set"},
        {fit + " --out " + (t.dir / "aabb.axes").string(), "--out: 'aabb' is the name of a built-in set"},
        {"flip --reference " + t.grass + " --test " + t.asphalt + " --ppd nan", "--ppd: 'nan' is not a number"},
        {"flip --reference " + t.grass + " --test " + t.asphalt + " --out " + (t.dir / "folder.exr").string(),
         "is a directory"},
        {"taa --size 1x1 --out " + (t.dir / "taa").string(), "--size: '1x1'"},
        {"taa --ppd 0 --out " + (t.dir / "taa").string(), "--ppd: '0' is not a number from 1 to 1000"},
        {"run --variant aabb-clip-n9 --current " + t.grass + " --history " + t.asphalt + " --format rgba8 --out " +
             (t.dir / "o.exr").string(),
         "--format: 'rgba8' is not rgba32f or rgba16f"},
        {"gne --out x", "kdop: 'gne' is not a command; the commands: list, gen,"},
    };
    for (const Case& c : cases) {
        auto r = test::run(kdop(c.args));
        EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
        EXPECT_TRUE(r.err.starts_with("kdop: ")) << "every message says whose it is: " << r.err;
        EXPECT_EQ(r.err.find("fitting"), std::string::npos) << "before the work: " << r.err;
    }
    EXPECT_EQ(fs::directory_iterator(t.dir / "folder"), fs::directory_iterator()) << "nothing written";
    EXPECT_FALSE(fs::exists(t.dir / "fitted.axes"));
    EXPECT_FALSE(fs::exists(t.dir / "taa"));

    // An output folder that cannot be made fails before a single variant is built.
    auto gen = test::run(kdop("gen --sets dop32 --out /proc/kdop-test"));
    EXPECT_EQ(gen.exit_code, 1);
    EXPECT_NE(gen.err.find("--out: /proc/kdop-test: cannot create files in /proc"), std::string::npos) << gen.err;
    EXPECT_EQ(gen.err.find("built"), std::string::npos) << gen.err;
}

TEST(CliTrust, MessagesShowWhatIsThereAndNoMore) {
    TrustRun t;
    // A byte-order mark at the start of a manifest is accepted, as in axis files.
    test::write_file(t.dir / "bom.manifest", "\xEF\xBB\xBF"
                                             "dop22-clip-n9\n");
    auto bom = test::run(kdop("list --manifest " + (t.dir / "bom.manifest").string()));
    EXPECT_EQ(bom.exit_code, 0) << bom.err;
    EXPECT_EQ(bom.out, "dop22-clip-n9\n");
    // Invisible bytes are shown, a long line is cut.
    test::write_file(t.dir / "odd.manifest", "dop22\xE2\x80\x8B-clip-n9\n" + std::string(100000, 'x') + "\n");
    auto odd = test::run(kdop("list --manifest " + (t.dir / "odd.manifest").string()));
    EXPECT_EQ(odd.exit_code, 1);
    EXPECT_NE(odd.err.find("'dop22\\xe2\\x80\\x8b-clip-n9' is not a variant name"), std::string::npos) << odd.err;
    test::write_file(t.dir / "long.manifest", std::string(100000, 'x') + "\n");
    auto long_line = test::run(kdop("list --manifest " + (t.dir / "long.manifest").string()));
    EXPECT_EQ(long_line.exit_code, 1);
    EXPECT_NE(long_line.err.find("(100000 bytes in all)"), std::string::npos) << long_line.err.substr(0, 400);
    EXPECT_LT(long_line.err.size(), 1000u);
    // `set:` with no file says so.
    test::write_file(t.dir / "set.manifest", "set:\ndop22-clip-n9\n");
    auto set = test::run(kdop("list --manifest " + (t.dir / "set.manifest").string()));
    EXPECT_EQ(set.exit_code, 1);
    EXPECT_NE(set.err.find("set.manifest:1: `set:` names no axis-set file"), std::string::npos) << set.err;
}

// A PNG refused for a value it cannot hold says so in kdop's words alone: libpng's own complaint
// about a file closed unwritten ("No IDATs written into file") came first.
TEST(CliTrust, ARefusedPngOutputSaysWhyInOneMessage) {
    TrustRun t;
    const std::string bright = (t.dir / "bright.exr").string();
    ASSERT_TRUE(write_image(bright, Image(8, 8, {2.0f, 0.5f, 0.5f, 1.0f})));
    auto r = test::run(kdop("run --variant aabb-clip-n9 --current " + bright + " --history " + bright + " --out " +
                            (t.dir / "out.png").string()));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("png stores values from 0 to 1, and pixel (0, 0) holds 2"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("libpng"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(t.dir / "out.png"));
}

// A PNG holds sRGB-encoded values: the clip runs on the linear values they decode to, as the CPU
// reference computes it on the same decoded values (not on the stored ones).
TEST(CliTrust, AnSrgbPngIsClippedOnItsDecodedLinearValues) {
    TrustRun t;
    const std::string current = (t.dir / "current.png").string(), history = (t.dir / "history.png").string();
    ASSERT_TRUE(write_image(current, *read_image(t.grass)));
    ASSERT_TRUE(write_image(history, *read_image(t.asphalt)));
    const std::string out = (t.dir / "clipped.exr").string();
    auto r =
        test::run(kdop("run --variant dop22-clip-n9 --current " + current + " --history " + history + " --out " + out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto clipped = read_image(out);
    ASSERT_TRUE(clipped) << clipped.error().message;
    const AxisSet dop22 = *resolve_axis_set("dop22");
    const Image decoded =
        reference_rectify(dop22, Mode::clip, Neighborhood::n9, *read_image(current), *read_image(history), 1.0);
    const Image stored =
        reference_rectify(dop22, Mode::clip, Neighborhood::n9, *read_image(current, 0, InputSpace::linear),
                          *read_image(history, 0, InputSpace::linear), 1.0);
    double worst = 0, worst_stored = 0;
    for (std::size_t i = 0; i < clipped->pixels.size(); ++i) {
        const glm::vec3 gpu(clipped->pixels[i]);
        worst = std::max<double>(worst, glm::distance(gpu, glm::vec3(decoded.pixels[i])));
        worst_stored = std::max<double>(worst_stored, glm::distance(gpu, glm::vec3(stored.pixels[i])));
    }
    EXPECT_LT(worst, 1e-5);
    EXPECT_GT(worst_stored, 1e-2) << "the stored values would give another clip";
}

// Includes that nest without end, and includes from outside the project.
TEST(CliTrust, ShaderIncludesStayInsideTheProjectAndNestAFiniteDepth) {
    test::TempDir dir;
    fs::create_directory(dir / "shaders");
    test::write_file(dir / "shaders" / "resolve.comp",
                     "#version 450\nlayout(local_size_x = 1) in;\n#include \"a.glsl\"\nvoid main() {}\n");
    test::write_file(dir / "shaders" / "a.glsl", "#include \"b.glsl\"\n");
    test::write_file(dir / "shaders" / "b.glsl", "#include \"a.glsl\"\n");
    test::write_file(dir / "secret.glsl", "float secret() { return 1.0; }\n");
    test::write_file(dir / "shaders" / "escape.comp", "#version 450\nlayout(local_size_x = 1) in;\n#include "
                                                      "\"../secret.glsl\"\nvoid main() {}\n");
    const std::string registry = test::kdop_gen_binary() + " registry --namespace x --sets dop22 --modes clip " +
                                 "--neighborhoods n9 --header " + (dir / "r.h").string() + " --source " +
                                 (dir / "r.cpp").string() + " --shaders ";
    // ulimit: before the fix this grew to 24 GB.
    auto cycle = test::run("ulimit -v 4000000; timeout 60 " + registry + (dir / "shaders" / "resolve.comp").string());
    EXPECT_EQ(cycle.exit_code, 1) << cycle.err;
    EXPECT_NE(cycle.err.find("includes nest deeper than 32: " + (dir / "shaders" / "resolve.comp").string() + " -> " +
                             (dir / "shaders" / "a.glsl").string() + " -> " + (dir / "shaders" / "b.glsl").string() +
                             " -> " + (dir / "shaders" / "a.glsl").string() + " -> ..."),
              std::string::npos)
        << cycle.err;
    auto escape = test::run(registry + (dir / "shaders" / "escape.comp").string());
    EXPECT_EQ(escape.exit_code, 1);
    EXPECT_NE(escape.err.find("escape.comp: #include \"../secret.glsl\" names "), std::string::npos) << escape.err;
    EXPECT_NE(escape.err.find("which is outside " + (dir / "shaders").string()), std::string::npos) << escape.err;
    // The same file is found through an include directory that holds it.
    auto allowed = test::run(registry + (dir / "shaders" / "escape.comp").string() + " --include-dirs " +
                             (dir / "shaders").string());
    EXPECT_EQ(allowed.exit_code, 1) << "still outside every allowed folder";
    EXPECT_FALSE(fs::exists(dir / "r.h"));
}

// The loop-form functions enable the extension their [[unroll]] needs, so they work where they are
// included: in kdop taa's frame shader and in a user's.
TEST(CliTrust, TaaRunsTheLoopForms) {
    test::TempDir dir;
    auto r = test::run(kdop("taa --size 64x36 --warmup 2 --frames 1 --timing-rounds 1 --sets dop22 --modes clip "
                            "--forms loop --scenes grass --out " +
                            (dir / "taa").string()));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(test::read_file(dir / "taa" / "taa.csv").find("\ndop22-clip-n9-loop,"), std::string::npos);
}

} // namespace
} // namespace kdop
