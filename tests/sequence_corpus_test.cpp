// A corpus of sequences named at once (sequence/sequence_corpus.h): a folder of sequences and a
// list file stand for the sequences they name, in a fixed order, and kdop taa and choose measure
// them as if each were given alone; an NSS root's sequences all at once.
#include "core/read_file.h"
#include "sequence/sequence_corpus.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace kdop {
namespace {

namespace fs = std::filesystem;

TEST(SequenceList, ReadsOneFolderALineRelativeToTheList) {
    auto folders = parse_sequence_list("a\n# held out\n\n/data/b\r\nc d\n", "lists/corpus.txt");
    ASSERT_TRUE(folders) << folders.error().message;
    EXPECT_EQ(*folders, (std::vector<std::string>{"lists/a", "/data/b", "lists/c d"}));
    auto last = parse_sequence_list("a", "corpus.txt");
    ASSERT_TRUE(last);
    EXPECT_EQ(*last, std::vector<std::string>{"a"});
}

TEST(SequenceList, RefusesAListOfNothingAndANulNamingTheLine) {
    auto empty = parse_sequence_list("# nothing\n\n", "corpus.txt");
    ASSERT_FALSE(empty);
    EXPECT_EQ(empty.error().message, "corpus.txt: a list of sequences that names none");
    auto nul = parse_sequence_list(std::string("a\nb\0c\n", 6), "corpus.txt");
    ASSERT_FALSE(nul);
    EXPECT_EQ(nul.error().message, "corpus.txt:2: a NUL byte in a folder's name");
}

TEST(SequenceCorpus, NssRootsListTheirSequencesInNumericOrder) {
    test::TempDir dir;
    for (const char* name : {"0010.json", "0002.json", "notes.json", "12.json", "0003.txt"})
        std::ofstream(dir / name) << "{}";
    auto names = nss_sequences(dir.path());
    ASSERT_TRUE(names) << names.error().message;
    EXPECT_EQ(*names, (std::vector<std::string>{"0002", "0010"}));
    test::TempDir none;
    EXPECT_FALSE(nss_sequences(none.path()));
}

// kdop's 2-D scenes written as four sequences: measured as a folder, as a list and one by one,
// every figure of a sequence is the same whichever way it was named.
TEST(CliCorpus, AFolderOrAListOfSequencesIsMeasuredAsEachGivenAlone) {
    test::TempDir dir;
    const std::string kdop = test::kdop_binary();
    auto s =
        test::run(kdop + " scene --scenes grass asphalt --size 32x18 --frames 8 --out " + (dir / "scenes").string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    fs::create_directory(dir / "lists");
    std::ofstream(dir / "lists" / "held_out.txt") << "# the held-out pair\n../scenes/grass-ghosting\r\n\n"
                                                  << (dir / "scenes" / "asphalt-shimmer").string() << "\n";
    const std::string taa = kdop + " taa --sets aabb dop16-grass --modes clip --warmup 3 --timing-rounds 2 "
                                   "--viewer-frames 0 --no-charts ";
    auto figures = [](const fs::path& out) {
        std::map<std::string, std::map<std::string, std::string>> by_row;
        for (auto row : test::csv_rows(read_input_file(out / "taa.csv").value_or("")))
            for (const auto& [column, value] : row)
                if (!column.starts_with("ms")) by_row[row["variant"] + " " + row["scene"]][column] = value;
        return by_row;
    };
    auto folder = test::run(taa + "--sequence " + (dir / "scenes").string() + " --out " + (dir / "folder").string());
    ASSERT_EQ(folder.exit_code, 0) << folder.err;
    auto list = test::run(taa + "--sequence " + (dir / "lists" / "held_out.txt").string() + " --out " +
                          (dir / "list").string());
    ASSERT_EQ(list.exit_code, 0) << list.err;
    const auto from_folder = figures(dir / "folder"), from_list = figures(dir / "list");
    EXPECT_EQ(from_folder.size(), 4u * 2u);
    ASSERT_EQ(from_list.size(), 2u * 2u);
    for (const char* sequence : {"grass-ghosting", "asphalt-shimmer"}) {
        auto alone = test::run(taa + "--sequence " + (dir / "scenes" / sequence).string() + " --out " +
                               (dir / sequence).string());
        ASSERT_EQ(alone.exit_code, 0) << alone.err;
        for (const auto& [row, values] : figures(dir / sequence)) {
            EXPECT_EQ(from_folder.at(row), values) << row;
            EXPECT_EQ(from_list.at(row), values) << row;
        }
    }
    // In byte order of the folders' names, whatever order the file system lists them in.
    const auto rows = test::csv_rows(read_input_file(dir / "folder" / "taa.csv").value_or(""));
    ASSERT_EQ(rows.size(), 8u);
    EXPECT_EQ(rows.front().at("scene"), "asphalt-ghosting");
    EXPECT_EQ(rows.back().at("scene"), "grass-shimmer");

    // Refused, nothing written: a path that names no sequence (exit 1), a sequence named twice
    // (exit 2), a list that names a folder without one.
    std::ofstream(dir / "lists" / "wrong.txt") << "../lists\n";
    const struct {
        std::string args;
        int exit_code;
        std::string says;
    } cases[] = {
        {(dir / "nothing").string(), 1, "neither a sequence's folder (with sequence.json), nor a folder of sequences"},
        {(dir / "lists" / "held_out.txt").string() + " " + (dir / "scenes").string(), 2, "is given twice"},
        {(dir / "lists" / "wrong.txt").string(), 1, "which is neither a sequence's folder"},
    };
    for (const auto& c : cases) {
        auto r = test::run(taa + "--sequence " + c.args + " --out " + (dir / "refused").string());
        EXPECT_EQ(r.exit_code, c.exit_code) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir / "refused") && !fs::is_empty(dir / "refused")) << c.args;
    }
}

// kdop choose takes the same: --fit from a list, --validate from a folder of sequences, with the
// figures of a run that names each sequence.
TEST(CliCorpus, ChooseFitsAndJudgesOnFoldersAndLists) {
    test::TempDir dir;
    const std::string kdop = test::kdop_binary();
    auto s =
        test::run(kdop + " scene --scenes grass asphalt --size 40x24 --frames 10 --out " + (dir / "scenes").string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    fs::create_directories(dir / "held");
    fs::copy(dir / "scenes" / "asphalt-ghosting", dir / "held" / "asphalt-ghosting", fs::copy_options::recursive);
    std::ofstream(dir / "fit.txt") << "scenes/grass-ghosting\n";
    const std::string choose = kdop + " choose --fit-axes 4 --sets aabb --warmup 3 --sample 1500 --timing-rounds 2 "
                                      "--no-charts ";
    auto named = test::run(choose + "--fit " + (dir / "scenes" / "grass-ghosting").string() + " --validate " +
                           (dir / "scenes" / "asphalt-ghosting").string() + " --out " + (dir / "named").string());
    ASSERT_EQ(named.exit_code, 0) << named.err;
    auto corpus = test::run(choose + "--fit " + (dir / "fit.txt").string() + " --validate " + (dir / "held").string() +
                            " --out " + (dir / "corpus").string());
    ASSERT_EQ(corpus.exit_code, 0) << corpus.err;
    auto a = test::csv_rows(read_input_file(dir / "named" / "candidates.csv").value_or(""));
    auto b = test::csv_rows(read_input_file(dir / "corpus" / "candidates.csv").value_or(""));
    ASSERT_EQ(a.size(), b.size());
    ASSERT_FALSE(a.empty());
    for (std::size_t r = 0; r < a.size(); ++r) EXPECT_EQ(a[r]["validation_ghosting"], b[r]["validation_ghosting"]);
}

// An NSS root holding many sequences: --nss-sequence all measures each, as --nss-sequence NNNN
// measures it alone.
TEST(CliCorpus, AllTheSequencesOfAnNssRoot) {
    test::TempDir dir;
    const std::string kdop = test::kdop_binary();
    auto s = test::run(kdop + " scene --scenes grass3d asphalt3d --size 32x18 --frames 6 --upscale 2 --layout nss " +
                       "--reference-samples 2 --out " + (dir / "nss").string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const std::string taa = kdop + " taa --sets aabb --modes clip --warmup 3 --timing-rounds 2 --viewer-frames 0 " +
                            "--no-charts --nss-range ldr --sequence " + (dir / "nss").string();
    auto all = test::run(taa + " --nss-sequence all --out " + (dir / "all").string());
    ASSERT_EQ(all.exit_code, 0) << all.err;
    auto one = test::run(taa + " --nss-sequence 0002 --out " + (dir / "one").string());
    ASSERT_EQ(one.exit_code, 0) << one.err;
    const auto rows = test::csv_rows(read_input_file(dir / "all" / "taa.csv").value_or(""));
    std::set<std::string> sequences;
    for (const auto& row : rows) sequences.insert(row.at("scene"));
    EXPECT_EQ(sequences, (std::set<std::string>{"0000", "0001", "0002", "0003"}));
    for (auto row : test::csv_rows(read_input_file(dir / "one" / "taa.csv").value_or(""))) {
        const auto same = std::ranges::find_if(
            rows, [&](const auto& r) { return r.at("variant") == row["variant"] && r.at("scene") == "0002"; });
        ASSERT_NE(same, rows.end()) << row["variant"];
        for (const char* column : {"ghosting", "shimmer"}) EXPECT_EQ(same->at(column), row[column]) << column;
    }
}

} // namespace
} // namespace kdop
