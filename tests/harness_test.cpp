// The measurement layer's parts on hand-made data: result tables in every format (RFC 4180 quoting,
// empty for unmeasured, rows that do not fit the columns refused), reading CSV back, run metadata,
// progress text, output sets and the memory budget.
#include "core/memory_budget.h"
#include "harness/csv_reader.h"
#include "harness/output_set.h"
#include "harness/printed_table.h"
#include "harness/progress.h"
#include "harness/rank_correlation.h"
#include "harness/run_metadata.h"
#include "harness/table.h"
#include "tests/test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <unistd.h>

namespace kdop {
namespace {
namespace fs = std::filesystem;

Table sample() {
    Table t({{"image", "", Shown::text},
             {"pixels", "", Shown::integer},
             {"mean_dist", "S", Shown::significant, 3, "mean"},
             {"rate", "", Shown::percent},
             {"front", "", Shown::flag}});
    t.add({"a, \"quoted\" name", std::int64_t(9), 0.30000000000000004, 0.184, true});
    t.add({"plain", std::int64_t(1225), Value(), NAN, false});
    return t;
}

TEST(Table, CsvQuotesPerRfc4180AndKeepsEveryDigit) {
    EXPECT_EQ(sample().csv(), "image,pixels,mean_dist,rate,front\n"
                              "\"a, \"\"quoted\"\" name\",9,0.30000000000000004,0.184,1\n"
                              "plain,1225,,,0\n");
    EXPECT_EQ(csv_field("line\nbreak"), "\"line\nbreak\"");
    EXPECT_EQ(csv_field("x"), "x");
}

TEST(Table, MarkdownShowsUnitsAndFormatsAndDashesWhatWasNotMeasured) {
    EXPECT_EQ(sample().markdown(), "| image | pixels | mean (S) | rate | front |\n"
                                   "|---|--:|--:|--:|---|\n"
                                   "| a, \"quoted\" name | 9 | 0.3 | 18.4% | yes |\n"
                                   "| plain | 1225 | – | – | no |\n");
    const std::string only[] = {"pixels", "image"};
    EXPECT_EQ(sample().markdown(only), "| pixels | image |\n|--:|---|\n| 9 | a, \"quoted\" name |\n| 1225 | plain |\n");
    Table big({{"n", "", Shown::significant, 3}});
    big.add({1234.5});
    EXPECT_EQ(big.shown(0, 0), "1234") << "integer digits are never lost to an exponent"; // 1234.5 rounds to even
}

TEST(Table, GnuplotAndJsonCarryTheSameRows) {
    const std::string columns[] = {"image", "mean_dist", "rate"};
    EXPECT_EQ(sample().gnuplot(columns), "\"a, 'quoted' name\" 0.3 0.184\n\"plain\" NaN NaN\n");
    const nlohmann::json json = sample().json();
    EXPECT_EQ(json["columns"][2]["unit"], "S");
    EXPECT_EQ(json["rows"][0]["pixels"], 9);
    EXPECT_EQ(json["rows"][0]["front"], true);
    EXPECT_TRUE(json["rows"][1]["mean_dist"].is_null());
    EXPECT_TRUE(json["rows"][1]["rate"].is_null());
}

// A row with more or fewer values than columns is refused at once, so a report's header and its
// values cannot drift apart the way positional format strings could.
TEST(Table, ARowThatDoesNotFitTheColumnsIsRefused) {
    Table t({{"a"}, {"b"}});
    EXPECT_THROW(t.add({1.0}), std::logic_error);
    EXPECT_THROW(t.add({1.0, 2.0, 3.0}), std::logic_error);
    EXPECT_THROW((void)t.column("c"), std::logic_error);
    t.add({1.0, 2.0});
    EXPECT_EQ(t.rows().size(), 1u);
    EXPECT_EQ(t.number(0, "b"), 2.0);
}

// Printed columns: each cell aligned in its column's width as its header is (left or right), the
// separator before every column but the first, and a cell wider than its column kept whole.
TEST(PrintedTable, HeaderAndRowsShareTheColumnsWidthsAndSeparators) {
    struct Row {
        std::string name;
        double value;
    };
    const PrintedColumns<Row> columns{{"name", -6, [](const Row& r) { return r.name; }},
                                      {"value", 8, [](const Row& r) { return fmt::format("{:.2f}", r.value); }},
                                      {"x2", 5, [](const Row& r) { return fmt::format("{:g}", 2 * r.value); }, "  "}};
    EXPECT_EQ(printed_header(columns), "name      value     x2");
    EXPECT_EQ(printed_row(columns, Row{"ab", 1.5}), "ab         1.50      3");
    EXPECT_EQ(printed_row(columns, Row{"longer name", 12345.678}), "longer name 12345.68  24691.4");
}

TEST(CsvReader, ReadsWhatTablesWriteAndNamesTheLineOfWhatItCannot) {
    auto csv = parse_csv(sample().csv(), "t.csv");
    ASSERT_TRUE(csv) << csv.error().message;
    EXPECT_EQ(csv->header.size(), 5u);
    ASSERT_EQ(csv->rows.size(), 2u);
    EXPECT_EQ(csv->rows[0][0], "a, \"quoted\" name");
    EXPECT_EQ(csv->rows[1][2], "");
    EXPECT_EQ(csv->lines[1], 3);
    EXPECT_EQ(csv->column("rate"), 3);

    auto multiline = parse_csv("a,b\r\n\"x\ny\",2\r\n\nz,3\n", "m.csv");
    ASSERT_TRUE(multiline) << multiline.error().message;
    EXPECT_EQ(multiline->rows[0][0], "x\ny");
    EXPECT_EQ(multiline->lines[1], 5) << "blank line skipped, line numbers kept";

    EXPECT_EQ(parse_csv("a,b\n1\n", "f.csv").error().message, "f.csv:2: 1 fields, the header has 2");
    EXPECT_EQ(parse_csv("a,b\n\"open,2\n", "q.csv").error().message, "q.csv:2: a quoted field is not closed");
    EXPECT_EQ(parse_csv("", "e.csv").error().message, "e.csv:1: empty; expected a header line");
}

// Spearman's rho: 1 for the same order whatever the scale, -1 reversed, ties sharing their mean
// rank (worked by hand: ranks 1, 2.5, 2.5, 4 against 1, 2, 3, 4 give 4.5 / sqrt(4.5 * 5)).
TEST(RankCorrelation, SpearmanComparesOrderingsNotValues) {
    EXPECT_DOUBLE_EQ(spearman({0.03, 0.05, 0.04}, {3, 500, 40}), 1.0);
    EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {9, 7, 5, 1}), -1.0);
    EXPECT_EQ(fractional_ranks({5, 1, 3, 3}), (std::vector<double>{4, 1, 2.5, 2.5}));
    EXPECT_NEAR(spearman({1, 2, 2, 3}, {1, 2, 3, 4}), 4.5 / std::sqrt(22.5), 1e-15);
    EXPECT_TRUE(std::isnan(spearman({1, 1, 1}, {1, 2, 3}))) << "no order to compare";
    EXPECT_TRUE(std::isnan(spearman({1}, {2})));
}

TEST(RunMetadata, CommandLineReproducesTheRun) {
    const char* argv[] = {"kdop", "accuracy", "--images", "my frame.exr", "it's.exr", "--seed", "3"};
    record_command_line(7, argv);
    RunMetadata run = describe_run();
    EXPECT_EQ(run.command, "kdop accuracy --images 'my frame.exr' 'it'\\''s.exr' --seed 3");
    EXPECT_EQ(run.version, "0.1.0");
    EXPECT_FALSE(run.commit.empty());
    run.seed = 3;
    const std::string header = metadata_markdown(run);
    EXPECT_NE(header.find("- command: `kdop accuracy --images 'my frame.exr'"), std::string::npos) << header;
    EXPECT_NE(header.find("- seed: 3\n"), std::string::npos) << header;
    EXPECT_EQ(header.find("- device:"), std::string::npos) << "no device took part";
    EXPECT_EQ(metadata_json(run)["seed"], 3);
}

TEST(Progress, ClockTextAndEstimate) {
    EXPECT_EQ(clock_text(0), "0:00");
    EXPECT_EQ(clock_text(65.4), "1:05");
    EXPECT_EQ(clock_text(3723), "1:02:03");
}

// In a log (stderr is not a terminal under ctest), a line per new item and per tenth of the total:
// a resolve's 100 frames of one sequence are 10 lines, not 100; the last step always shows.
TEST(Progress, ALogGetsALinePerItemAndPerTenthNotPerStep) {
    testing::internal::CaptureStderr();
    {
        Progress progress("TAA", 101);
        for (int i = 0; i < 100; ++i) progress.advance("grass");
        progress.advance("asphalt");
    }
    const std::string log = testing::internal::GetCapturedStderr();
    EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 11) << log;
    EXPECT_NE(log.find("[  1/101] TAA grass"), std::string::npos) << log;
    EXPECT_NE(log.find("[ 11/101] TAA grass"), std::string::npos) << log;
    EXPECT_NE(log.find("[101/101] TAA asphalt"), std::string::npos) << log;

    testing::internal::CaptureStderr();
    {
        Progress progress("built", 3);
        for (const char* item : {"a", "b", "c"}) progress.advance(item);
    }
    const std::string each = testing::internal::GetCapturedStderr();
    EXPECT_EQ(std::count(each.begin(), each.end(), '\n'), 3) << each;
}

TEST(OutputSet, WritesTablesAsCsvAndJsonTogetherOrNotAtAll) {
    test::TempDir dir;
    auto outputs = OutputSet::prepare(dir / "out");
    ASSERT_TRUE(outputs) << outputs.error().message;
    EXPECT_FALSE(fs::exists(dir / "out")) << "nothing is created before the work is done";
    RunMetadata run = describe_run();
    outputs->add_table("sample", sample(), run);
    outputs->add("report.md", "# report\n");
    ASSERT_TRUE(outputs->write());
    EXPECT_EQ(test::read_file(dir / "out" / "sample.csv"), sample().csv());
    const auto json = nlohmann::json::parse(test::read_file(dir / "out" / "sample.json"));
    EXPECT_EQ(json["run"]["kdop_version"], "0.1.0");
    EXPECT_EQ(json["rows"].size(), 2u);

    auto refused = OutputSet::prepare("/proc/kdop-out", "--out");
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("--out: /proc/kdop-out"), std::string::npos);
}

TEST(MemoryBudget, RefusesWhatCannotFitAndSaysHowMuch) {
    ASSERT_GT(available_memory(), 0u) << "/proc/meminfo has MemAvailable on Linux";
    EXPECT_TRUE(check_memory("small", 1 << 20));
    auto huge = check_memory("--size 99999x99999", available_memory() * 2);
    ASSERT_FALSE(huge);
    EXPECT_EQ(huge.error().message.rfind("--size 99999x99999: needs about ", 0), 0u) << huge.error().message;
    EXPECT_EQ(rectify_pass_bytes(16384, 16384), 32ull << 30);
}

// After return_large_blocks_when_freed(), a large block freed is gone from the process, even after
// a larger one freed before it, which would otherwise have raised glibc's threshold above it and
// left the second in a heap that keeps what is freed.
TEST(MemoryBudget, LargeBlocksGoBackToTheSystemWhenFreed) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer's allocator is not glibc's";
#endif
    return_large_blocks_when_freed();
    auto resident = [] { // bytes, from /proc/self/statm's second field (pages)
        std::ifstream statm("/proc/self/statm");
        std::uint64_t size = 0, pages = 0;
        statm >> size >> pages;
        return pages * std::uint64_t(sysconf(_SC_PAGESIZE));
    };
    for (std::size_t mib : {30, 20}) {
        const std::uint64_t before = resident();
        auto block = std::make_unique<char[]>(mib << 20);
        std::memset(block.get(), 1, mib << 20); // touched, so resident
        EXPECT_GE(resident(), before + (mib << 19)) << mib << " MiB";
        block.reset();
        EXPECT_LT(resident(), before + (mib << 18)) << mib << " MiB, freed";
    }
}

} // namespace
} // namespace kdop
