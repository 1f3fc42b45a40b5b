// An output folder holds one run's outputs (issue 58, finding 5): what an earlier kdop run wrote
// there and a new run does not is removed with the new set, as part of it; nothing else is touched,
// no listing can lead a removal outside the folder, and a failed set leaves the earlier one whole.
#include "core/input_files.h"
#include "core/output_listing.h"
#include "harness/output_set.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace kdop {
namespace {
namespace fs = std::filesystem;

std::vector<std::string> files_under(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir)) out.push_back(fs::relative(e.path(), dir).string());
    std::sort(out.begin(), out.end());
    return out;
}

Result<void> write_set(const fs::path& dir, const std::vector<std::string>& names) {
    auto set = OutputSet::prepare(dir);
    if (!set) return std::unexpected(set.error());
    for (const std::string& name : names) set->add(name, "made for " + name);
    return set->write();
}

TEST(OutputListing, IsSortedAndRefusesEntriesOutsideItsFolderNamingTheLine) {
    const std::string text = output_listing_text({"b.csv", "a/x.png", "b.csv", "/abs", "../up"});
    EXPECT_EQ(text.substr(text.find('\n') + 1), "a/x.png\nb.csv\n");
    auto parsed = parse_output_listing(text, "L");
    ASSERT_TRUE(parsed) << parsed.error().message;
    EXPECT_EQ(*parsed, (std::vector<std::string>{"a/x.png", "b.csv"}));
    for (const std::string& bad : {"/etc/passwd", "../x", "a/../../x", "a//b", "./a", "a/.", "tab\there", "x\ry"}) {
        auto refused = parse_output_listing("# comment\nok.csv\n" + bad + "\n", "out/.kdop-outputs");
        ASSERT_FALSE(refused) << bad;
        EXPECT_NE(refused.error().message.find("out/.kdop-outputs:3: "), std::string::npos) << refused.error().message;
    }
}

TEST(OutputListing, ASecondRunRemovesWhatOnlyTheFirstWroteAndNothingElse) {
    test::TempDir dir;
    const fs::path out = dir / "out";
    ASSERT_TRUE(write_set(out, {"report.md", "charts/old.png", "frames/a/0001.exr", "frames/a/0002.exr"}));
    test::write_file(out / "notes.txt", "the user's own");
    fs::create_directories(out / "frames" / "b");
    test::write_file(out / "frames" / "b" / "mine.exr", "the user's own too");
    ASSERT_TRUE(write_set(out, {"report.md", "frames/a/0001.exr"}));
    EXPECT_EQ(files_under(out), (std::vector<std::string>{".kdop-outputs", "frames", "frames/a", "frames/a/0001.exr",
                                                          "frames/b", "frames/b/mine.exr", "notes.txt", "report.md"}));
    EXPECT_EQ(test::read_file(out / ".kdop-outputs"), output_listing_text({"report.md", "frames/a/0001.exr"}));
}

// A set that fails leaves the earlier one whole, its stale files included.
TEST(OutputListing, AFailedSetLeavesTheEarlierOneAsItWas) {
    test::TempDir dir;
    const fs::path out = dir / "out";
    ASSERT_TRUE(write_set(out, {"report.md", "old/chart.png"}));
    const std::vector<std::string> before = files_under(out);
    auto set = OutputSet::prepare(out);
    ASSERT_TRUE(set);
    set->add("report.md", "new");
    set->add(std::vector<OutputWriter>{
        {out / "image.exr", [](const fs::path&) -> Result<void> { return fail("the image writer failed"); }}});
    ASSERT_FALSE(set->write());
    EXPECT_EQ(files_under(out), before);
    EXPECT_EQ(test::read_file(out / "report.md"), "made for report.md");
}

// A listing is a file anyone may edit or replace: a link on the way out of the folder, a link in
// place of a listed file, and this run's inputs are never removed.
TEST(OutputListing, NoListingLeadsARemovalOutsideTheFolderOrToAnInput) {
    test::TempDir dir;
    const fs::path out = dir / "out", outside = dir / "outside";
    fs::create_directories(outside);
    test::write_file(outside / "precious.txt", "keep");
    ASSERT_TRUE(write_set(out, {"report.md"}));
    fs::create_directory_symlink(outside, out / "via");
    fs::create_symlink(outside / "precious.txt", out / "link.txt");
    test::write_file(out / "input.exr", "an input of this run");
    protect_inputs(); // as a kdop process does
    note_input(out / "input.exr");
    test::write_file(out / ".kdop-outputs", "via/precious.txt\nlink.txt\ninput.exr\n");
    const bool written = bool(write_set(out, {"report.md"}));
    protect_inputs(false);
    ASSERT_TRUE(written);
    EXPECT_EQ(test::read_file(outside / "precious.txt"), "keep");
    EXPECT_TRUE(fs::is_symlink(out / "link.txt"));
    EXPECT_TRUE(fs::exists(out / "input.exr"));
    // A listing that names a path outside is refused before the work, naming its line.
    test::write_file(out / ".kdop-outputs", "report.md\n../outside/precious.txt\n");
    auto refused = OutputSet::prepare(out);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find(".kdop-outputs:2: '../outside/precious.txt'"), std::string::npos)
        << refused.error().message;
}

// The finding as a user met it: a second kdop taa into the same folder, on another sequence, left
// the first sequence's charts, pictures and viewer frames beside its own.
TEST(CliOutputListing, ASecondTaaRunLeavesOnlyItsOwnFiles) {
    test::TempDir dir;
    auto scene = test::run({test::kdop_binary(), "scene", "--scenes", "grass", "--frames", "5", "--size", "24x16",
                            "--out", (dir / "scenes").string()});
    ASSERT_EQ(scene.exit_code, 0) << scene.err;
    auto taa = [&](const std::string& sequence) {
        return test::run({test::kdop_binary(), "taa", "--warmup", "2", "--sets", "aabb", "--modes", "clip",
                          "--viewer-frames", "2", "--out", (dir / "out").string(), "--sequence",
                          (dir / "scenes" / sequence).string()});
    };
    auto first = taa("grass-ghosting");
    ASSERT_EQ(first.exit_code, 0) << first.err;
    ASSERT_TRUE(fs::exists(dir / "out" / "trade-grass-ghosting.png"));
    auto second = taa("grass-shimmer");
    ASSERT_EQ(second.exit_code, 0) << second.err;
    for (const std::string& file : files_under(dir / "out"))
        EXPECT_EQ(file.find("grass-ghosting"), std::string::npos) << file;
    EXPECT_TRUE(fs::exists(dir / "out" / "trade-grass-shimmer.png"));
}

} // namespace
} // namespace kdop
