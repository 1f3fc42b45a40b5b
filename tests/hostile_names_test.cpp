// Reliability, round 4 (issue 58): names from outside kdop (a sequence's folder, a background's file,
// a test image's file) as every program kdop writes a script for, every file it names after them
// and every format that carries them. Each name is refused up front, clearly, or carried faithfully;
// none runs a command and none writes outside --out.
#include "core/escaped_text.h"
#include "core/file_name.h"
#include "core/shown_text.h"
#include "harness/gnuplot.h"
#include "harness/subprocess.h"
#include "images/image_io.h"
#include "tests/test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace kdop {
namespace {
namespace fs = std::filesystem;

// Names kdop must carry as they are: each would be code to gnuplot, a shell or a page if it were
// pasted in. The first two ran `touch PWNED` through a chart's title before the fix.
const std::vector<std::string> kCarried = {"a'.system('touch PWNED').'", "b`touch PWNED`", "c$(touch PWNED)@x",
                                           "d\"q\\back\\", "e <b>&amp; {x}_y^z"};

// Names no file of kdop's can be named after: each is refused before the work, naming why.
struct Refused {
    std::string name, reason;
};
const std::vector<Refused> kRefused = {
    {"two\nlines", "control byte (\\x0a)"},
    {"caf\xe9", "not valid UTF-8"},
    {"evil\xe2\x80\xaegnp.exr", "U+202E"},
    {std::string(200, 'n'), "200 bytes long"},
};

std::vector<std::string> kdop_args(std::initializer_list<std::string> args) {
    std::vector<std::string> out{test::kdop_binary()};
    out.insert(out.end(), args);
    return out;
}

// Every file under `dir`, as paths relative to it.
std::vector<std::string> files_under(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir)) out.push_back(fs::relative(e.path(), dir).string());
    std::sort(out.begin(), out.end());
    return out;
}

TEST(HostileNames4, GnuplotStringsHoldEveryByteAndRunNothing) {
    if (find_program("gnuplot").empty()) GTEST_SKIP() << "gnuplot is not installed";
    test::TempDir dir;
    std::vector<std::string> texts = kCarried;
    for (const Refused& r : kRefused) texts.push_back(r.name);
    texts.push_back(std::string("\x01\x7f\xff all 256: ") + "\t\r");
    std::string all;
    for (int b = 1; b < 256; ++b) all += char(b);
    texts.push_back(all);
    std::string script;
    for (std::size_t i = 0; i < texts.size(); ++i)
        script += fmt::format("set print {}\nprint {}\n", gnuplot_string((dir / fmt::format("{}.txt", i)).string()),
                              gnuplot_string(texts[i]));
    test::write_file(dir / "t.gp", script);
    auto r = test::run({find_program("gnuplot").string(), "t.gp"}, dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (std::size_t i = 0; i < texts.size(); ++i)
        EXPECT_EQ(test::read_file(dir / fmt::format("{}.txt", i)), texts[i] + "\n") << shown_text(texts[i]);
    EXPECT_FALSE(fs::exists(dir / "PWNED"));
}

TEST(HostileNames4, NamesNoFileCanHaveAreFoundWhereTheyAreRead) {
    for (const Refused& r : kRefused) {
        auto problem = name_problem(r.name);
        ASSERT_TRUE(problem) << shown_text(r.name);
        EXPECT_NE(problem->find(r.reason), std::string::npos) << *problem;
    }
    for (const std::string& name :
         {std::string(""), std::string("."), std::string(".."), std::string("a/b"), std::string("\xc0\xaf"),
          std::string("\xed\xa0\x80"), std::string("\xf4\x90\x80\x80"), std::string("x\xc2\x85"),
          std::string("\xe2\x81\xa6isolate")})
        EXPECT_TRUE(name_problem(name)) << shown_text(name);
    for (const std::string& name : kCarried) EXPECT_FALSE(name_problem(name)) << shown_text(name);
    for (const std::string& name : {std::string("caf\xc3\xa9"), std::string("\xe6\x97\xa5\xe6\x9c\xac"),
                                    std::string("\xf0\x9f\x8e\xae"), std::string(kMaxNameBytes, 'n')})
        EXPECT_FALSE(name_problem(name)) << shown_text(name);
}

// A sequence of a few frames at 24x16 as `kdop scene` writes them, to copy under hostile names.
fs::path template_sequence(const fs::path& dir) {
    auto r = test::run(kdop_args(
        {"scene", "--scenes", "grass", "--frames", "5", "--size", "24x16", "--out", (dir / "template").string()}));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return dir / "template" / "grass-ghosting";
}

// Each name as a sequence's folder in one `kdop taa` run: the charts are drawn (before, gnuplot ran
// `touch PWNED` or failed and the charts were left out), every file named after a sequence is in
// --out under its name, and the JSON and the page hold the name as it is.
TEST(CliHostileNames, TaaCarriesEverySequenceNameFaithfully) {
    test::TempDir dir;
    const fs::path source = template_sequence(dir.path());
    std::vector<std::string> args = kdop_args({"taa", "--warmup", "2", "--sets", "aabb", "--modes", "clip",
                                               "--viewer-frames", "1", "--out", "out", "--sequence"});
    for (const std::string& name : kCarried) {
        fs::create_directories(dir / "sequences");
        fs::copy(source, dir / "sequences" / name, fs::copy_options::recursive);
        args.push_back((dir / "sequences" / name).string());
    }
    auto r = test::run(args, dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("left out"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "PWNED"));
    const fs::path out = dir / "out";
    const auto json = nlohmann::json::parse(test::read_file(out / "taa.json"));
    const std::string page = test::read_file(out / "report.html");
    for (const std::string& name : kCarried) {
        EXPECT_TRUE(fs::is_regular_file(out / ("trade-" + name + ".png"))) << name;
        EXPECT_TRUE(fs::is_regular_file(out / ("over-time-" + name + ".png"))) << name;
        EXPECT_TRUE(std::any_of(json["rows"].begin(), json["rows"].end(), [&](const nlohmann::json& row) {
            return row.value("scene", "") == name;
        })) << name;
        EXPECT_NE(page.find(html_text(name)), std::string::npos) << name;
    }
    for (const std::string& file : files_under(dir.path()))
        EXPECT_TRUE(file.starts_with("out") || file.starts_with("sequences") || file.starts_with("template")) << file;
}

TEST(CliHostileNames, TaaRefusesSequenceNamesNoFileCanHaveBeforeTheWork) {
    test::TempDir dir;
    const fs::path source = template_sequence(dir.path());
    for (const Refused& refused : kRefused) {
        fs::create_directories(dir / "sequences");
        const fs::path sequence = dir / "sequences" / refused.name;
        fs::copy(source, sequence, fs::copy_options::recursive);
        auto r = test::run(kdop_args({"taa", "--warmup", "2", "--sets", "aabb", "--modes", "clip", "--out",
                                      (dir / "out").string(), "--sequence", sequence.string()}));
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_NE(r.err.find(refused.reason), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("rename the folder"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir / "out"));
    }
}

// A background named ...png would name its scene "..": its sequence folder was <out>/.., which
// replaced the sequence beside --out (finding 2). Now it is refused and that sequence is untouched.
TEST(CliHostileNames, SceneAndTaaRefuseBackgroundsWhoseStemNamesNoFile) {
    test::TempDir dir;
    const fs::path kept = template_sequence(dir.path()).parent_path();
    fs::create_directories(dir / "bg");
    const std::string before = test::read_file(kept / "sequence.json");
    for (const std::string& name : {std::string(".."), std::string("."), std::string("tab\tname")}) {
        const fs::path background = dir / "bg" / (name + ".png");
        ASSERT_TRUE(write_image(background.string(), Image(24, 16, {0.5f, 0.25f, 0.125f, 1})));
        auto scene = test::run(kdop_args({"scene", "--background", background.string(), "--animate", "on", "--size",
                                          "24x16", "--frames", "3", "--out", (kept / "out").string()}));
        EXPECT_EQ(scene.exit_code, 2) << scene.err;
        EXPECT_NE(scene.err.find("rename the file"), std::string::npos) << scene.err;
        auto taa = test::run(kdop_args({"taa", "--background", background.string(), "--size", "24x16", "--warmup", "2",
                                        "--frames", "2", "--sets", "aabb", "--out", (dir / "taa").string()}));
        EXPECT_EQ(taa.exit_code, 2) << taa.err;
        EXPECT_FALSE(fs::exists(dir / "taa"));
    }
    EXPECT_EQ(test::read_file(kept / "sequence.json"), before);
    EXPECT_FALSE(fs::exists(kept / "out"));
}

// A sequence called grass-ghosting beside --scenes grass wrote its frames over the scene's own
// grass-ghosting sequence's (finding 4): every name a file is named after must be distinct.
TEST(CliHostileNames, ASequenceNamedAsASceneSequenceIsRefused) {
    test::TempDir dir;
    const fs::path source = template_sequence(dir.path());
    for (const std::string name : {"grass-ghosting", "grass-shimmer", "grass"}) {
        fs::copy(source, dir / name, fs::copy_options::recursive);
        auto r = test::run(kdop_args({"taa", "--scenes", "grass", "--size", "24x16", "--warmup", "2", "--frames", "2",
                                      "--sets", "aabb", "--write-frames", "--out", (dir / "out").string(), "--sequence",
                                      (dir / name).string()}));
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_NE(r.err.find("rename the folder"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir / "out"));
    }
}

// kdop choose names its sets, tables, report, chart and manifest after the sequences it fits to and
// judges on: the names reach each as data.
TEST(CliHostileNames, ChooseCarriesSequenceNamesFaithfully) {
    test::TempDir dir;
    const fs::path source = template_sequence(dir.path());
    const std::string fit = kCarried[0], validate = kCarried[3];
    fs::create_directories(dir / "sequences");
    for (const std::string& name : {fit, validate})
        fs::copy(source, dir / "sequences" / name, fs::copy_options::recursive);
    auto r = test::run(kdop_args({"choose", "--fit", (dir / "sequences" / fit).string(), "--validate",
                                  (dir / "sequences" / validate).string(), "--fit-axes", "4", "--sets", "aabb",
                                  "--warmup", "2", "--sample", "500", "--timing-rounds", "2", "--out", "out"}),
                       dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("left out"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "PWNED"));
    const std::string report = test::read_file(dir / "out" / "choice.md");
    for (const std::string& name : {fit, validate})
        EXPECT_NE(report.find(markdown_text(name)), std::string::npos) << name << "\n" << report;
    EXPECT_TRUE(fs::is_regular_file(dir / "out" / "choice.png"));
    auto listed = test::run(kdop_args({"list", "--manifest", (dir / "out" / "kdop.manifest").string()}));
    EXPECT_EQ(listed.exit_code, 0) << listed.err;
    for (const std::string& file : files_under(dir.path()))
        EXPECT_TRUE(file.starts_with("out") || file.starts_with("sequences") || file.starts_with("template")) << file;
}

// kdop flip's histogram titles and kdop accuracy's charts carry test images' names as data (before,
// a line break in a name lost the histogram).
TEST(CliHostileNames, FlipAndAccuracyChartsCarryFileNames) {
    test::TempDir dir;
    const fs::path reference = dir / "reference.png";
    ASSERT_TRUE(write_image(reference.string(), Image(16, 16, {0.5f, 0.25f, 0.125f, 1})));
    std::vector<std::string> names = kCarried;
    names.push_back("two\nlines"); // a test image's name is only shown, so it may hold one
    for (const std::string& name : names) {
        const fs::path test_image = dir / (name + ".png");
        ASSERT_TRUE(write_image(test_image.string(), Image(16, 16, {0.25f, 0.25f, 0.5f, 1})));
        auto flip = test::run(kdop_args({"flip", "--cpu", "--reference", reference.string(), "--test",
                                         test_image.string(), "--histogram", "histogram.png"}),
                              dir.path());
        EXPECT_EQ(flip.exit_code, 0) << flip.err;
        EXPECT_EQ(flip.err.find("left out"), std::string::npos) << flip.err;
        EXPECT_TRUE(fs::is_regular_file(dir / "histogram.png")) << name;
        fs::remove(dir / "histogram.png");
        auto accuracy = test::run(kdop_args({"accuracy", "--sets", "aabb", "--modes", "clip", "--neighborhoods", "n9",
                                             "--volume-samples", "0", "--images", test_image.string(), "--out", "acc"}),
                                  dir.path());
        EXPECT_EQ(accuracy.exit_code, 0) << accuracy.err;
        EXPECT_EQ(accuracy.err.find("left out"), std::string::npos) << accuracy.err;
        fs::remove_all(dir / "acc");
    }
    EXPECT_FALSE(fs::exists(dir / "PWNED"));
}

} // namespace
} // namespace kdop
