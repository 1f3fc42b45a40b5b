// Reliability, round 4 (issue 58), what is neither a name (hostile_names_test.cpp), an output
// folder's listing (output_listing_test.cpp) nor a signal (signal_test.cpp): a figure never measured
// is absent, not perfect; progress stays one line a step, whatever a name holds; an option that
// would be silently ignored is refused.
#include "core/shown_text.h"
#include "harness/progress.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace kdop {
namespace {
namespace fs = std::filesystem;

std::vector<std::string> kdop_args(std::initializer_list<std::string> args) {
    std::vector<std::string> out{test::kdop_binary()};
    out.insert(out.end(), args);
    return out;
}

// kdop's two sequences of the grass scene, 5 frames of 24x16, in dir/scenes.
fs::path scene_sequences(const fs::path& dir) {
    auto r = test::run(kdop_args(
        {"scene", "--scenes", "grass", "--frames", "5", "--size", "24x16", "--out", (dir / "scenes").string()}));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return dir / "scenes";
}

TEST(ProgressLines, StayOneLineWhateverANameHolds) {
    const std::string forged = "a\nkdop taa: done\r\x1b[2K\xe2\x80\xae"
                               "gnp.exr";
    EXPECT_EQ(one_line_text(forged), "a\\x0akdop taa: done\\x0d\\x1b[2K\\xe2\\x80\\xaegnp.exr");
    EXPECT_EQ(terminal_text("ok\n\tcaf\xc3\xa9 \xe2\x81\xa6x\xc2\x85"), "ok\n\tcaf\xc3\xa9 \\xe2\\x81\\xa6x\\xc2\\x85");
    testing::internal::CaptureStderr();
    {
        Progress progress("step\nforged", 2);
        progress.advance(forged);
        progress.advance("second\n");
    }
    const std::string printed = testing::internal::GetCapturedStderr();
    EXPECT_EQ(std::count(printed.begin(), printed.end(), '\n'), 2) << printed;
    EXPECT_EQ(printed.find("\xe2\x80\xae"), std::string::npos) << printed;
}

// A shimmer sequence with a camera cut on every frame has no two successive outputs of one
// history: its shimmer was written as 0 (perfect), and shown as 0.0000 (finding 9).
TEST(CliReliability4, ShimmerNeverMeasuredIsAbsentNotZero) {
    test::TempDir dir;
    const fs::path sequence = scene_sequences(dir.path()) / "grass-shimmer";
    auto json = nlohmann::json::parse(test::read_file(sequence / "sequence.json"));
    for (auto& frame : json["frames"]) frame["camera_cut"] = true;
    test::write_file(sequence / "sequence.json", json.dump(1));
    auto r = test::run(kdop_args({"taa", "--sequence", sequence.string(), "--warmup", "2", "--sets", "aabb", "--modes",
                                  "clip", "--no-charts", "--viewer-frames", "0", "--out", (dir / "out").string()}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("shimmer not measured"), std::string::npos) << r.err;
    const auto rows = test::csv_rows(test::read_file(dir / "out" / "taa.csv"));
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_EQ(rows[0].at("shimmer"), "");
    const auto table = nlohmann::json::parse(test::read_file(dir / "out" / "taa.json"));
    EXPECT_TRUE(table["rows"][0]["shimmer"].is_null()) << table["rows"][0].dump();
    const std::string report = test::read_file(dir / "out" / "report.md");
    EXPECT_EQ(report.find("0.0000"), std::string::npos) << report;
    EXPECT_NE(report.find("shimmer where every measured frame follows a camera cut"), std::string::npos) << report;
}

// --picture-frame picks the frame of a sequence's ghosting picture; with only kdop's scenes, or only
// sequences meant for shimmer, it chose nothing and was silently ignored.
TEST(CliReliability4, APictureFrameNothingShowsIsRefused) {
    test::TempDir dir;
    const fs::path scenes = scene_sequences(dir.path());
    const std::vector<std::vector<std::string>> ignored = {
        {"--scenes", "grass", "--size", "24x16", "--frames", "2"},
        {"--sequence", (scenes / "grass-shimmer").string()},
    };
    for (const std::vector<std::string>& sources : ignored) {
        std::vector<std::string> args = kdop_args(
            {"taa", "--warmup", "2", "--sets", "aabb", "--picture-frame", "3", "--out", (dir / "out").string()});
        args.insert(args.end(), sources.begin(), sources.end());
        auto r = test::run(args);
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_NE(r.err.find("--picture-frame 3: picks the frame of each --sequence's ghosting picture"),
                  std::string::npos)
            << r.err;
        EXPECT_FALSE(fs::exists(dir / "out"));
    }
}

// Every refusal of what a command line asked for exits 2, as docs/cli.md says, before any work
// (issue 59, finding 7: a --warmup longer than a sequence and `kdop show dop32-clip-n7` exited 1).
// One table over the commands; each case is refused in well under a second.
TEST(CliReliability4, EveryUsageRefusalExits2BeforeAnyWork) {
    test::TempDir dir;
    const fs::path scenes = scene_sequences(dir.path());
    const std::string ghosting = (scenes / "grass-ghosting").string(), out = (dir / "out").string();
    const std::string image = (scenes / "grass-ghosting" / "color" / "0001.exr").string();
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"show", "dop32-clip-n7"}, "'dop32-clip-n7' is not a variant name"},
        {{"show", "nosuch-clip-n9"}, "no axis set is named 'nosuch'"},
        {{"run", "--variant", "dop32-clip-n7", "--current", image, "--history", image, "--out", out + ".exr"},
         "'dop32-clip-n7' is not a variant name"},
        {{"taa", "--sequence", ghosting, "--sets", "aabb", "--out", out},
         "5 frames, and --warmup 100 leaves none to measure; give a shorter warm-up, e.g. --warmup 1"},
        {{"taa", "--sequence", (scenes / "grass-shimmer").string(), "--warmup", "2", "--picture-frame", "3", "--out",
          out},
         "--picture-frame 3: picks the frame of each --sequence's ghosting picture"},
        {{"choose", "--fit", ghosting, "--holdout", "1", "--fit-axes", "4", "4", "--out", out}, "given twice"},
        {{"choose", "--fit", ghosting, "--holdout", "1", "--budget-ms", "0x10", "--out", out}, "is not a number"},
        {{"flip", "--cpu", "--reference", image, "--test", image, "--out", image}, "is an input of this run"},
        {{"optimize", "--images", image, "--axes", "4", "--name", "mine", "--out", image}, "is an input of this run"},
    };
    for (const auto& [args, expected] : cases) {
        std::vector<std::string> line{test::kdop_binary()};
        line.insert(line.end(), args.begin(), args.end());
        auto r = test::run(line);
        EXPECT_EQ(r.exit_code, 2) << args[0] << " " << args[1] << ": " << r.err;
        EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir / "out")) << args[0] << " " << args[1];
        EXPECT_FALSE(fs::exists(dir / "out.exr")) << args[0] << " " << args[1];
    }
}

// kdop choose's held-out sequence, made of the fit's own frame files (cp -al, hard links), held
// nothing out and was judged as if it did (finding 12); an --out that holds a fit sequence's files
// could have one replaced, found only at the end (finding 10).
TEST(CliReliability4, ChooseRefusesHeldOutFramesThatAreTheFitsAndAnOutInsideASequence) {
    test::TempDir dir;
    const fs::path fit = scene_sequences(dir.path()) / "grass-ghosting", linked = dir / "linked";
    fs::create_directories(linked);
    for (const auto& entry : fs::recursive_directory_iterator(fit)) {
        const fs::path to = linked / fs::relative(entry.path(), fit);
        if (entry.is_directory())
            fs::create_directories(to);
        else if (entry.path().filename() == "sequence.json")
            fs::copy_file(entry.path(), to);
        else
            fs::create_hard_link(entry.path(), to);
    }
    auto choose = [&](const fs::path& validate, const fs::path& out) {
        return test::run(kdop_args({"choose", "--fit", fit.string(), "--validate", validate.string(), "--fit-axes", "4",
                                    "--sets", "aabb", "--warmup", "2", "--sample", "500", "--timing-rounds", "2",
                                    "--no-charts", "--out", out.string()}));
    };
    auto linked_run = choose(linked, dir / "out");
    EXPECT_EQ(linked_run.exit_code, 2) << linked_run.err;
    EXPECT_NE(linked_run.err.find("is the same file as --fit's"), std::string::npos) << linked_run.err;
    EXPECT_FALSE(fs::exists(dir / "out"));
    const fs::path other = scene_sequences(dir / "other") / "grass-ghosting";
    const std::string before = test::read_file(fit / "sequence.json");
    auto inside = choose(other, fit);
    EXPECT_EQ(inside.exit_code, 2) << inside.err;
    EXPECT_NE(inside.err.find("--out"), std::string::npos) << inside.err;
    EXPECT_FALSE(fs::exists(fit / "choice.md"));
    EXPECT_EQ(test::read_file(fit / "sequence.json"), before);
}

} // namespace
} // namespace kdop
