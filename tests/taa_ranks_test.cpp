// kdop taa over MPI ranks (temporal/taa_ranks.h): sources balanced over the ranks, each measured by
// one, and rank 0 writing the files a run without mpirun writes, whatever the rank count.
#include "harness/ranks.h"
#include "temporal/taa_ranks.h"
#include "tests/test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

namespace kdop {
namespace {

namespace fs = std::filesystem;

TEST(TaaRanks, BalanceGivesTheLargestFirstToTheLeastLoadedRank) {
    // 9 -> 0; 7 -> 1; 5 -> 2; 4 -> 2 (5); 3 -> 1 (7); 1 -> 0 (9); equal costs keep their order.
    EXPECT_EQ(balance_over(std::vector<double>{4, 9, 1, 7, 3, 5}, 3), (std::vector<int>{2, 0, 0, 1, 1, 2}));
    EXPECT_EQ(balance_over(std::vector<double>{2, 2, 2, 2}, 2), (std::vector<int>{0, 1, 0, 1}));
    EXPECT_EQ(balance_over(std::vector<double>{5, 1}, 4), (std::vector<int>{0, 1}));
    EXPECT_EQ(balance_over(std::vector<double>{5, 1, 3}, 1), (std::vector<int>{0, 0, 0}));
}

// What a rank sends rank 0 comes back exactly: every double's bits, NaN where a figure is not
// measured, a variant without a worst frame, an HDR range.
TEST(TaaRanks, AMeasuredSourceSurvivesItsEncoding) {
    MeasuredSource source;
    EvaluationRow& row = source.rows.emplace_back();
    row.variant = 3, row.source = "grass \"ghosting\"", row.means = {0.1, NAN, 1.0 / 3.0};
    row.against_reference = true, row.range = ColorRange::hdr, row.notes = {"color/0042.exr: black"};
    row.per_frame = {{"grass-ghosting", 7, {0.25, NAN, 1e-300}}, {"grass-ghosting", 8, {}}};
    row.upscale = 1.5;
    source.picture = "ghosting-grass.png";
    ViewerSequence& viewed = source.viewed.emplace_back();
    viewed.name = "grass-ghosting", viewed.scene = "grass", viewed.figure = 1, viewed.range = ColorRange::hdr;
    viewed.truth = "reference", viewed.map = "HDR-FLIP", viewed.width = 32, viewed.height = 18;
    viewed.frames = {3, 9}, viewed.worst = {9, ViewerSequence::kNone}, viewed.figures = {{0.5, NAN}, {0.75, NAN}};
    viewed.variants = 2;

    auto back = measured_source_from(measured_source_bytes(source));
    ASSERT_TRUE(back) << back.error().message;
    ASSERT_EQ(back->rows.size(), 1u);
    const EvaluationRow& r = back->rows[0];
    EXPECT_EQ(r.variant, 3u);
    EXPECT_EQ(r.source, row.source);
    ASSERT_EQ(r.means.size(), 3u);
    EXPECT_EQ(r.means[0], 0.1);
    EXPECT_TRUE(std::isnan(r.means[1]));
    EXPECT_EQ(r.means[2], 1.0 / 3.0);
    EXPECT_TRUE(r.against_reference);
    EXPECT_EQ(r.range, ColorRange::hdr);
    EXPECT_EQ(r.notes, row.notes);
    ASSERT_EQ(r.per_frame.size(), 2u);
    EXPECT_EQ(r.per_frame[0].index, 7u);
    EXPECT_EQ(r.per_frame[0].values[2], 1e-300);
    EXPECT_TRUE(r.per_frame[1].values.empty());
    EXPECT_EQ(r.upscale, 1.5);
    EXPECT_EQ(back->picture, source.picture);
    ASSERT_EQ(back->viewed.size(), 1u);
    const ViewerSequence& v = back->viewed[0];
    EXPECT_EQ(v.worst, viewed.worst);
    EXPECT_EQ(v.frames, viewed.frames);
    EXPECT_EQ(v.figures[1][0], 0.75);
    EXPECT_TRUE(std::isnan(v.figures[1][1]));
    EXPECT_EQ(v.range, ColorRange::hdr);
    EXPECT_EQ(std::tie(v.name, v.scene, v.truth, v.map, v.width, v.height, v.variants, v.figure),
              std::tie(viewed.name, viewed.scene, viewed.truth, viewed.map, viewed.width, viewed.height,
                       viewed.variants, viewed.figure));
    EXPECT_FALSE(measured_source_from("not CBOR"));
}

// `kdop scene --scenes asphalt` into `out`: its ghosting and shimmer sequences of `frames` frames.
void write_asphalt_sequences(const fs::path& out, const std::string& size, int frames) {
    auto s = test::run(fmt::format("{} scene --scenes asphalt --size {} --frames {} --out {}", test::kdop_binary(),
                                   size, frames, out.string()));
    ASSERT_EQ(s.exit_code, 0) << s.err;
}

// Every file under `dir`, relative to it.
std::set<std::string> files_under(const fs::path& dir) {
    std::set<std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.is_regular_file()) files.insert(fs::relative(entry.path(), dir).string());
    return files;
}

// mpirun -np 1, 2, 3 on one of kdop's scenes and a folder of two sequences: every file but those
// that hold the timings or the date is the same byte for byte (taa.csv but its timed columns); each
// source is measured by one rank, every rank measures some, one progress stream is printed. A
// usage error is one, exit 2; a frame a rank cannot read stops every rank, the frame named once,
// nothing written.
TEST(CliTaaRanks, TheSameFilesOnAnyRankCount) {
#ifndef KDOP_MPIEXEC
    GTEST_SKIP() << "kdop was built without MPI (libopenmpi-dev)";
#else
    test::TempDir dir;
    const fs::path scenes = dir / "scenes";
    ASSERT_NO_FATAL_FAILURE(write_asphalt_sequences(scenes, "32x18", 8));
    auto taa = [&](const std::string& launch, const fs::path& out, const fs::path& sequences) {
        return test::run(launch + test::kdop_binary() +
                         " taa --scenes grass --size 32x18 --sets aabb dop16-grass --modes clip "
                         "--warmup 3 --frames 4 --timing-rounds 2 --viewer-frames 2 --write-frames --sequence " +
                         sequences.string() + " --out " + out.string());
    };
    const fs::path alone = dir / "alone";
    auto a = taa("", alone, scenes);
    ASSERT_EQ(a.exit_code, 0) << a.err;
    // The files that hold timings (the ms columns, the trade charts) or the date.
    const std::set<std::string> timed{"taa.csv", "taa.json", "taa_frames.json", "report.md", "report.html"};
    auto untimed = [](const fs::path& csv) {
        auto rows = test::csv_rows(test::read_file(csv));
        for (auto& row : rows) row.erase("ms"), row.erase("ms_q1"), row.erase("ms_q3"), row.erase("ms_noise");
        return rows;
    };
    const std::set<std::string> written = files_under(alone);
    EXPECT_GT(written.size(), 100u); // the pictures, the viewer's frames, every output frame
    EXPECT_EQ(nlohmann::json::parse(test::read_file(alone / "taa.json"))["run"].count("ranks"), 0u);
    nlohmann::json shares3;
    for (int ranks : {1, 2, 3}) {
        SCOPED_TRACE(fmt::format("{} ranks", ranks));
        const fs::path out = dir / fmt::format("ranks{}", ranks);
        auto r = taa(test::mpirun_np() + std::to_string(ranks) + " ", out, scenes);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        ASSERT_EQ(files_under(out), written);
        for (const std::string& file : written)
            if (!timed.contains(file) && !file.starts_with("trade-")) {
                EXPECT_EQ(test::read_file(out / file), test::read_file(alone / file)) << file;
            }
        EXPECT_EQ(untimed(out / "taa.csv"), untimed(alone / "taa.csv"));
        EXPECT_EQ(r.out.find("kdop taa: "), r.out.rfind("kdop taa: ")) << "printed once\n" << r.out;
        if (ranks == 1) continue;
        // One progress stream, rank 0's, counting every rank's frames: the scene's 2 x 7 and the
        // sequences' 2 x 8.
        EXPECT_NE(r.err.find(fmt::format("and {} ranks,", ranks)), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("[30/30] TAA of"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("[31/"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("Gathering"), r.err.rfind("Gathering")) << r.err;
        // Each of the 3 sources measured by exactly one rank, every rank measuring some.
        const nlohmann::json shares = nlohmann::json::parse(test::read_file(out / "taa.json"))["run"]["ranks"];
        ASSERT_EQ(shares.size(), std::size_t(ranks)) << shares;
        std::multiset<std::string> measured;
        for (const auto& share : shares) {
            EXPECT_FALSE(share["measured"].empty()) << shares;
            for (const auto& name : share["measured"]) measured.insert(name.get<std::string>());
        }
        EXPECT_EQ(measured, (std::multiset<std::string>{"grass", "asphalt-ghosting", "asphalt-shimmer"}));
        const std::string report = test::read_file(out / "report.md");
        EXPECT_NE(report.find(fmt::format("- ranks: {} (MPI)", ranks)), std::string::npos) << report;
        if (ranks == 3) shares3 = shares;
    }

    const fs::path refused = dir / "refused";
    auto u = test::run(test::mpirun_np() + "2 " + test::kdop_binary() + " taa --frames 0 --out " + refused.string());
    EXPECT_EQ(u.exit_code, 2) << u.err;
    EXPECT_NE(u.err.find("--frames"), std::string::npos) << u.err;
    EXPECT_FALSE(fs::exists(refused));

    // A frame of a sequence rank 2 measures, cut short: every rank stops, the frame named once.
    ASSERT_FALSE(shares3.empty());
    std::string broken;
    for (const auto& name : shares3[2]["measured"])
        if (name.get<std::string>().find('-') != std::string::npos) broken = name.get<std::string>();
    ASSERT_FALSE(broken.empty()) << shares3;
    fs::copy(scenes, dir / "broken", fs::copy_options::recursive);
    const fs::path frame = dir / "broken" / broken / "color" / "0006.exr";
    ASSERT_TRUE(fs::exists(frame));
    fs::resize_file(frame, 100);
    const fs::path stopped = dir / "stopped";
    auto b = taa(test::mpirun_np() + "3 ", stopped, dir / "broken");
    EXPECT_EQ(b.exit_code, 1) << b.err;
    EXPECT_NE(b.err.find("rank 2 of 3: " + broken + ": "), std::string::npos) << b.err;
    EXPECT_NE(b.err.find(broken + "/color/0006.exr"), std::string::npos) << b.err;
    EXPECT_EQ(b.err.find("0006.exr"), b.err.rfind("0006.exr")) << "one rank speaks\n" << b.err;
    EXPECT_FALSE(fs::exists(stopped) && !fs::is_empty(stopped));
#endif
}

// The largest k of the progress lines "[k/total]" in `log`.
std::size_t furthest_step(const std::string& log, std::size_t total) {
    std::size_t furthest = 0;
    const std::string end = fmt::format("/{}]", total);
    for (std::size_t at = log.find(end); at != std::string::npos; at = log.find(end, at + 1)) {
        const std::size_t open = log.rfind('[', at);
        if (open != std::string::npos) furthest = std::max<std::size_t>(furthest, std::stoul(log.substr(open + 1)));
    }
    return furthest;
}

// A rank that cannot read a frame stops the others early: rank 0, with a long share (a
// scene of 2 x 603 frames), stops within a few of its frames instead of measuring them all, and
// the failing rank's error is the one printed.
TEST(CliTaaRanks, AFailingRankStopsTheOthersEarly) {
#ifndef KDOP_MPIEXEC
    GTEST_SKIP() << "kdop was built without MPI (libopenmpi-dev)";
#else
    test::TempDir dir;
    const fs::path scenes = dir / "scenes";
    ASSERT_NO_FATAL_FAILURE(write_asphalt_sequences(scenes, "32x18", 8));
    // Rank 1 measures the two short sequences (the balance gives the scene to rank 0), each cut
    // short from its fourth frame (the first is read by every rank as the sources are opened).
    for (const char* sequence : {"asphalt-ghosting", "asphalt-shimmer"})
        fs::resize_file(scenes / sequence / "color" / "0003.exr", 100);
    const fs::path out = dir / "out";
    auto r = test::run(test::mpirun_np() + "2 " + test::kdop_binary() +
                       " taa --scenes grass --size 64x36 --sets aabb --modes clip --warmup 3 --frames 600 "
                       "--timing-rounds 1 --viewer-frames 0 --sequence " +
                       scenes.string() + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("rank 1 of 2: asphalt-"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("/color/0003.exr"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("stopped"), std::string::npos) << "the failure is said, not the stop\n" << r.err;
    // 2 x 603 frames of the scene and 2 x 8 of the sequences: rank 0 stopped well before the end
    // (without the stop: [1100/1222] and more).
    const std::size_t total = 2 * 603 + 2 * 8;
    EXPECT_LT(furthest_step(r.err, total), total / 2) << r.err;
    EXPECT_FALSE(fs::exists(out) && !fs::is_empty(out));

    // Rank 0 failing stops rank 1: two sequences of 300 frames, the first of them rank 0's. Eight
    // variants make each of rank 1's frames slow enough that the head start it has while rank 0
    // times the variants (a second or two) is a few dozen frames, not half its share.
    const fs::path long_ones = dir / "long";
    ASSERT_NO_FATAL_FAILURE(write_asphalt_sequences(long_ones, "64x36", 300));
    fs::resize_file(long_ones / "asphalt-ghosting" / "color" / "0003.exr", 100);
    auto z = test::run(test::mpirun_np() + "2 " + test::kdop_binary() +
                       " taa --sets aabb dop16-grass dop22 dop32 --modes clip varclip --warmup 3 --timing-rounds 1 "
                       "--viewer-frames 0 --sequence " +
                       long_ones.string() + " --out " + out.string());
    EXPECT_EQ(z.exit_code, 1) << z.err;
    EXPECT_NE(z.err.find("kdop: asphalt-ghosting: "), std::string::npos) << z.err;
    // 2 x 300 frames: rank 1 stopped well before the end of its 300 (without the stop: [303/600]).
    EXPECT_LT(furthest_step(z.err, 600), 150u) << z.err;
    EXPECT_FALSE(fs::exists(out) && !fs::is_empty(out));
#endif
}

} // namespace
} // namespace kdop
