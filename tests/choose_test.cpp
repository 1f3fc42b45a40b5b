// kdop choose (optimize/choose.h): the recommendation rule on constructed candidates whose answer
// is known, the manifest it writes, and the command's held-out figures against kdop taa's.
#include "optimize/choice_report.h"
#include "optimize/choose.h"
#include "test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>

namespace kdop {
namespace {

namespace fs = std::filesystem;

Candidate candidate(const std::string& set, bool fitted, std::size_t ops, double held_out, double fit = NAN) {
    Candidate c;
    c.ms = double(ops) / 100; // a time that follows the float ops, for the ms budget
    c.key = {set, Mode::clip, Neighborhood::n9};
    c.fitted = fitted;
    c.float_ops = ops;
    c.validation_ghosting = held_out;
    c.fit_ghosting = fit;
    return c;
}

// The fitted sets win on the frames they were fitted to and lose on the held-out ones: a built-in
// set is recommended, within a budget or against a target, and the report says the fitted lost.
TEST(Choose, RecommendsTheLeastHeldOutGhostingWithinTheBudget) {
    const std::vector<Candidate> candidates{
        candidate("fitted4", true, 190, 0.030, 0.010), candidate("fitted8", true, 300, 0.026, 0.008),
        candidate("aabb", false, 87, 0.040),           candidate("dop16-grass", false, 354, 0.024),
        candidate("dop22", false, 381, 0.025),         candidate("dop32", false, 520, 0.0245)};
    // No budget: the least held-out ghosting of all.
    EXPECT_EQ(recommend(candidates, {}, std::nullopt).chosen, 3u);
    // Within 360 float ops: dop16-grass still; within 300: fitted8; within 100: the box.
    EXPECT_EQ(recommend(candidates, {.ops = 360}, std::nullopt).chosen, 3u);
    EXPECT_EQ(recommend(candidates, {.ops = 300}, std::nullopt).chosen, 1u);
    EXPECT_EQ(recommend(candidates, {.ops = 100}, std::nullopt).chosen, 2u);
    // A budget in median ms works the same way: within 3.6 ms, dop16-grass (3.54 ms); within 3 ms, fitted8.
    EXPECT_EQ(recommend(candidates, {.ms = 3.6}, std::nullopt).chosen, 3u);
    EXPECT_EQ(recommend(candidates, {.ms = 3.0}, std::nullopt).chosen, 1u);
    const Recommendation none = recommend(candidates, {.ops = 50}, std::nullopt);
    EXPECT_FALSE(none.chosen);
    EXPECT_NE(none.why.find("at most 50 float ops"), std::string::npos) << none.why;
    // A target: the cheapest that reaches it, not the one that ghosts least.
    EXPECT_EQ(recommend(candidates, {}, 0.0255).chosen, 3u);
    EXPECT_EQ(recommend(candidates, {}, 0.0265).chosen, 1u);
    EXPECT_EQ(recommend(candidates, {}, 0.05).chosen, 2u);
    EXPECT_FALSE(recommend(candidates, {}, 0.02).chosen);
    // Of equal ghosting, the cheaper; a candidate with no held-out figure never qualifies.
    const std::vector<Candidate> tied{candidate("a", false, 300, 0.02), candidate("b", false, 200, 0.02),
                                      candidate("c", false, 10, NAN)};
    EXPECT_EQ(recommend(tied, {}, std::nullopt).chosen, 1u);
    EXPECT_EQ(recommend(tied, {}, 0.5).chosen, 1u);

    // The front, cheapest first: the box, fitted4, fitted8 and dop16-grass; dop22 and dop32 cost
    // more than dop16-grass and ghost more.
    EXPECT_EQ(pareto_front(candidates), (std::vector<std::size_t>{2, 0, 1, 3}));

    ChooseResult result{candidates, recommend(candidates, {}, std::nullopt), {}, {"level1"}, {"level2"}, {}};
    const std::string md = choice_markdown(result, {}, {});
    EXPECT_NE(
        md.find("**The fitted sets lost on the held-out frames**: the best built-in candidate, dop16-grass-clip-n9, "
                "ghosts 0.0240 there, the best fitted one, fitted8-clip-n9, 0.0260 (on the frames it was "
                "fitted to, 0.0080)"),
        std::string::npos)
        << md;
    EXPECT_EQ(choice_manifest(result), "# kdop choose's recommendation (choice.md says why).\ndop16-grass-clip-n9\n");
}

// choice.md says the space the sets were fitted and judged in, the color map as given, every digit
// (gamma:1.00000001 was written as gamma:1), as the fitted files' color_map: lines record it.
TEST(Choose, TheReportRecordsTheColorMapAsGiven) {
    ChooseOptions options;
    auto map = parse_color_map("gamma:1.00000001");
    ASSERT_TRUE(map) << map.error().message;
    options.evaluation.resolve.color_map = *map;
    ChooseResult result;
    result.candidates = {candidate("aabb", false, 87, 0.03)};
    result.recommendation.chosen = 0;
    const std::string md = choice_markdown(result, options, {});
    EXPECT_NE(md.find("the held-out frames left out, in gamma:1.00000001 colors)"), std::string::npos) << md;
    EXPECT_NE(md.find("measures it (bilinear history, gamma:1.00000001 colors, current weight"), std::string::npos)
        << md;
}

// A fitted set recommended: the manifest names its variant and its file, and kdop gen builds
// exactly that variant from them.
TEST(CliChoose, TheManifestOfAFittedSetBuildsExactlyThatVariant) {
    test::TempDir dir;
    const std::string fitted =
        "name: fitted4\nprovenance: constructed by the test\nvec3(1, 0, 0),\nvec3(0, 1, 0),\nvec3(0, 0, 1),\n"
        "vec3(0.57735, 0.57735, 0.57735)\n";
    test::write_file(dir / "fitted4.axes", fitted);
    ChooseResult result;
    result.candidates = {candidate("fitted4", true, 190, 0.02), candidate("aabb", false, 87, 0.03)};
    result.recommendation.chosen = 0;
    result.fitted_files = {{"fitted4.axes", fitted}};
    result.fit_sequences = {"level1"};
    result.validate_sequences = {"level2"};
    const std::string manifest = choice_manifest(result);
    EXPECT_EQ(manifest, "# kdop choose's recommendation (choice.md says why).\nset: fitted4.axes\nfitted4-clip-n9\n");
    test::write_file(dir / "kdop.manifest", manifest);
    auto r = test::run(test::kdop_binary() + " gen --manifest " + (dir / "kdop.manifest").string() + " --out " +
                       (dir / "gen").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::string> built;
    for (const auto& entry : fs::directory_iterator(dir / "gen"))
        if (entry.path().extension() == ".spv") built.push_back(entry.path().stem().string());
    EXPECT_EQ(built, (std::vector<std::string>{"fitted4-clip-n9"}));
}

// A --sets file's set recommended: kdop.manifest names it with a `set:` line and the file is copied
// beside it (a manifest reads set files only from its own folder), so kdop list, kdop gen and
// kdop-gen registry (what kdop_add_variants(MANIFEST) runs) take the manifest; without the line,
// `kdop list --manifest` exited 1. A --sets file already in --out under its set's name is named
// where it is and kept; a set file kdop would write over an input is refused before the fit.
TEST(CliChoose, AGivenSetRecommendedIsCopiedBesideTheManifest) {
    test::TempDir dir;
    auto kdop = [](const std::string& args) { return test::run(test::kdop_binary() + " " + args); };
    const fs::path scenes = dir / "scenes", out = dir / "choose";
    auto s = kdop("scene --scenes grass asphalt --size 32x24 --frames 8 --out " + scenes.string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    // Three axes along R, G and B: as cheap as a clip gets, so the cheapest that reaches any target.
    const std::string mine = "name: mine\nprovenance: the test's\nvec3(1, 0, 0),\nvec3(0, 1, 0),\nvec3(0, 0, 1)\n";
    fs::create_directories(dir / "sets");
    test::write_file(dir / "sets" / "my file.axes", mine);
    const std::string choose = "choose --fit " + (scenes / "grass-ghosting").string() + " --validate " +
                               (scenes / "asphalt-ghosting").string() +
                               " --fit-axes 3 --warmup 2 --sample 500 --timing-rounds 2 --no-charts "
                               "--target-ghosting 1 ";
    auto r = kdop(choose + "--sets '" + (dir / "sets" / "my file.axes").string() + "' --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string manifest = "# kdop choose's recommendation (choice.md says why).\nset: mine.axes\nmine-clip-n9\n";
    EXPECT_EQ(test::read_file(out / "kdop.manifest"), manifest);
    EXPECT_EQ(test::read_file(out / "mine.axes"), mine);
    const std::string md = test::read_file(out / "choice.md");
    EXPECT_NE(md.find("with its set's file, mine.axes, a copy of "), std::string::npos) << md;

    const std::string listed = (out / "kdop.manifest").string();
    auto list = kdop("list --manifest " + listed);
    EXPECT_EQ(list.exit_code, 0) << list.err;
    EXPECT_NE(list.out.find("mine-clip-n9"), std::string::npos) << list.out;
    auto gen = kdop("gen --manifest " + listed + " --out " + (dir / "gen").string());
    EXPECT_EQ(gen.exit_code, 0) << gen.err;
    EXPECT_TRUE(fs::exists(dir / "gen" / "mine-clip-n9.spv"));
    const fs::path registry = dir / "registry";
    auto built = test::run(test::kdop_gen_binary() + " registry --manifest " + listed + " --header " +
                           (registry / "v.h").string() + " --source " + (registry / "v.cpp").string() +
                           " --namespace choice --json " + (registry / "v.json").string());
    EXPECT_EQ(built.exit_code, 0) << built.err;
    EXPECT_NE(test::read_file(registry / "v.json").find("mine-clip-n9"), std::string::npos);

    // The copy given back from --out: named where it is, and kept though this run does not write it.
    auto again = kdop(choose + "--sets " + (out / "mine.axes").string() + " --out " + out.string());
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(test::read_file(out / "kdop.manifest"), manifest);
    EXPECT_EQ(test::read_file(out / "mine.axes"), mine);
    EXPECT_EQ(kdop("list --manifest " + listed).exit_code, 0);

    // A --sets file at the name a fitted set is written as: refused before any work, left as it was.
    const fs::path clash = dir / "clash";
    fs::create_directories(clash);
    test::write_file(clash / "fitted3.axes", mine);
    auto refused = kdop(choose + "--sets " + (clash / "fitted3.axes").string() + " --out " + clash.string());
    EXPECT_EQ(refused.exit_code, 2) << refused.err;
    EXPECT_NE(refused.err.find("kdop choose writes fitted3.axes there, and that file is"), std::string::npos)
        << refused.err;
    EXPECT_EQ(refused.err.find("fitting"), std::string::npos) << refused.err;
    EXPECT_EQ(test::read_file(clash / "fitted3.axes"), mine);
}

// Two candidates of one set name, a color map the resolve cannot compute in and a warm-up longer
// than a sequence: each a wrong command line, exit 2, refused before the fit (the clashes were
// found after both fits, exit 1, gamma:1e-300 when its fitted file was parsed back), naming the
// option given (--fit or --validate, not --sequence); nothing is written.
TEST(CliChoose, ClashesAndBadValuesAreRefusedBeforeTheFit) {
    test::TempDir dir;
    auto kdop = [](const std::string& args) { return test::run(test::kdop_binary() + " " + args); };
    const fs::path scenes = dir / "scenes", out = dir / "choose";
    ASSERT_EQ(kdop("scene --scenes grass --size 32x24 --frames 8 --out " + scenes.string()).exit_code, 0);
    ASSERT_EQ(kdop("scene --scenes asphalt --size 32x24 --frames 6 --out " + scenes.string() + "6").exit_code, 0);
    const std::string axes = "provenance: the test's\nvec3(1, 0, 0),\nvec3(0, 1, 0),\nvec3(0, 0, 1)\n";
    test::write_file(dir / "f4.axes", "name: fitted4\n" + axes);
    test::write_file(dir / "d22.axes", "name: dop22\n" + axes);
    const std::string choose = "choose --fit " + (scenes / "grass-ghosting").string() + " --validate " +
                               (scenes.string() + "6") + "/asphalt-ghosting --sample 500 --out " + out.string() + " ";
    const std::vector<std::pair<std::string, std::string>> cases{
        {"--fit-axes 4 4 --warmup 2", "--fit-axes: 4 is given twice"},
        {"--fit-axes 4 --sets aabb " + (dir / "f4.axes").string() + " --warmup 2",
         "its set is named 'fitted4', as the set --fit-axes 4 fits is"},
        {"--fit-axes 4 --sets " + (dir / "d22.axes").string() + " --warmup 2", "the name of a built-in set"},
        {"--fit-axes 4 --color-map gamma:1e-300 --warmup 2", "1e-300 is 0 in float"},
        {"--fit-axes 4 --budget-ms 0x10 --warmup 2", "--budget-ms: '0x10' is not a number"},
        {"--fit-axes 4 --warmup 8",
         "--fit: " + (scenes / "grass-ghosting").string() + ": 8 frames, and --warmup 8 leaves none to measure"},
        {"--fit-axes 4 --warmup 6", "--validate: " + (scenes.string() + "6") +
                                        "/asphalt-ghosting: 6 frames, and --warmup 6 leaves none to measure"}};
    for (const auto& [args, message] : cases) {
        auto r = kdop(choose + args);
        EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
        EXPECT_EQ(r.err.find("fitting"), std::string::npos) << "before the fit: " << args << "\n" << r.err;
        EXPECT_FALSE(fs::exists(out)) << args;
    }
}

// The held-out figures are kdop taa's on the held-out sequences, to the last digit (the same
// evaluation), for the fitted set as for the built-in ones; without held-out sequences, or with a
// sequence both fitted to and held out, the command line is refused and nothing is written.
TEST(CliChoose, HeldOutFiguresAreKdopTaasOnTheHeldOutSequences) {
    test::TempDir dir;
    auto kdop = [](const std::string& args) { return test::run(test::kdop_binary() + " " + args); };
    const fs::path scenes = dir / "scenes", out = dir / "choose", taa = dir / "taa";
    auto s = kdop("scene --scenes grass asphalt --size 48x32 --frames 12 --out " + scenes.string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const std::string fit = (scenes / "grass-ghosting").string(), held = (scenes / "asphalt-ghosting").string();
    auto r = kdop("choose --fit " + fit + " --validate " + held +
                  " --fit-axes 4 --sets aabb dop22 --warmup 3 --sample 2000 --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* file :
         {"candidates.csv", "candidates.json", "choice.md", "choice.png", "fitted4.axes", "kdop.manifest"})
        EXPECT_TRUE(fs::exists(out / file)) << file;
    EXPECT_NE(test::read_file(out / "choice.md").find("](choice.png)"), std::string::npos);
    auto t = kdop("taa --sequence " + held + " --sets aabb dop22 " + (out / "fitted4.axes").string() +
                  " --modes clip --warmup 3 --timing-rounds 2 --no-charts --viewer-frames 0 --out " + taa.string());
    ASSERT_EQ(t.exit_code, 0) << t.err;
    const auto candidates = test::csv_rows(test::read_file(out / "candidates.csv"));
    const auto rows = test::csv_rows(test::read_file(taa / "taa.csv"));
    ASSERT_EQ(candidates.size(), 3u);
    for (auto c : candidates) {
        SCOPED_TRACE(c["variant"]);
        EXPECT_EQ(c["fitted"], c["variant"] == "fitted4-clip-n9" ? "1" : "0");
        auto row = std::find_if(rows.begin(), rows.end(), [&](auto& row) { return row.at("variant") == c["variant"]; });
        ASSERT_NE(row, rows.end());
        EXPECT_EQ(c["validation_ghosting"], row->at("ghosting"));
        EXPECT_EQ(c["validation_ghosting_median"], row->at("ghosting_median"));
        EXPECT_EQ(c["validation_ghosting_p95"], row->at("ghosting_p95"));
        EXPECT_FALSE(c["fit_ghosting"].empty());
    }
    // The manifest selects exactly the recommended variant, the one choose printed.
    const std::string manifest = test::read_file(out / "kdop.manifest");
    const std::string chosen = manifest.substr(manifest.rfind('\n', manifest.size() - 2) + 1);
    EXPECT_NE(r.out.find("kdop choose: " + chosen.substr(0, chosen.size() - 1) + ":"), std::string::npos) << r.out;

    // Each candidate's pass timed; a budget no candidate meets recommends nothing and writes no manifest.
    for (auto c : candidates) EXPECT_GT(std::stod(c["ms"]), 0.0) << c["variant"];
    const fs::path tight = dir / "tight";
    auto n = kdop("choose --fit " + fit + " --validate " + held +
                  " --fit-axes 4 --sets aabb --warmup 3 --sample 2000 --timing-rounds 2 --no-charts --budget-ms 1e-9 "
                  "--out " +
                  tight.string());
    ASSERT_EQ(n.exit_code, 0) << n.err;
    EXPECT_NE(n.out.find("no recommendation: no candidate's clip costs at most 1e-09 ms"), std::string::npos) << n.out;
    EXPECT_FALSE(fs::exists(tight / "kdop.manifest"));
    EXPECT_FALSE(fs::exists(tight / "choice.png"));
    EXPECT_TRUE(fs::exists(tight / "choice.md"));

    for (const std::string& bad : {std::string("--fit ") + fit, "--fit " + fit + " --validate " + fit}) {
        const fs::path refused = dir / "refused";
        auto b = kdop("choose " + bad + " --fit-axes 4 --warmup 3 --out " + refused.string());
        EXPECT_EQ(b.exit_code, 2) << bad << "\n" << b.err;
        EXPECT_NE(b.err.find("--validate"), std::string::npos) << b.err;
        EXPECT_FALSE(fs::exists(refused)) << bad;
    }
}

// --holdout: blocks of frames of the fitted sequence are left out of the fit and judged on; the
// held-out figures are the means of kdop taa's per-frame figures on exactly those frames, and a
// sequence too short to hold any out is refused.
TEST(CliChoose, HoldoutJudgesOnBlocksOfFramesLeftOutOfTheFit) {
    test::TempDir dir;
    auto kdop = [](const std::string& args) { return test::run(test::kdop_binary() + " " + args); };
    const fs::path scenes = dir / "scenes", out = dir / "choose", taa = dir / "taa";
    auto s = kdop("scene --scenes grass --size 48x32 --frames 12 --out " + scenes.string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const std::string fit = (scenes / "grass-ghosting").string();
    auto r = kdop("choose --fit " + fit + " --holdout 2 --fit-axes 4 --sets aabb --warmup 3 --sample 2000 --out " +
                  out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // Measured frames 3..11: blocks [3, 4] fitted, [5, 6] held out, [7, 8] fitted, [9, 10] held out, [11] fitted.
    const std::set<std::string> held_out{"5", "6", "9", "10"};
    EXPECT_NE(test::read_file(out / "fitted4.axes").find("8 of 12 frames, every other block of 2 after 3 held out"),
              std::string::npos)
        << test::read_file(out / "fitted4.axes");
    EXPECT_NE(test::read_file(out / "choice.md").find("every other block of 2 frames"), std::string::npos);
    auto t = kdop("taa --sequence " + fit + " --sets aabb " + (out / "fitted4.axes").string() +
                  " --modes clip --warmup 3 --timing-rounds 2 --no-charts --viewer-frames 0 --out " + taa.string());
    ASSERT_EQ(t.exit_code, 0) << t.err;
    const auto frames = test::csv_rows(test::read_file(taa / "taa_frames.csv"));
    const auto candidates = test::csv_rows(test::read_file(out / "candidates.csv"));
    ASSERT_EQ(candidates.size(), 2u);
    for (auto c : candidates) {
        SCOPED_TRACE(c["variant"]);
        double held = 0, fitted = 0;
        int held_count = 0, fitted_count = 0;
        for (auto f : frames)
            if (f["variant"] == c["variant"]) {
                const bool out_of_fit = held_out.count(f["frame"]) > 0;
                (out_of_fit ? held : fitted) += std::stod(f["ghosting"]);
                ++(out_of_fit ? held_count : fitted_count);
            }
        ASSERT_EQ(held_count, 4);
        ASSERT_EQ(fitted_count, 5);
        EXPECT_DOUBLE_EQ(std::stod(c["validation_ghosting"]), held / 4);
        EXPECT_DOUBLE_EQ(std::stod(c["fit_ghosting"]), fitted / 5);
    }
    const fs::path refused = dir / "refused";
    auto b = kdop("choose --fit " + fit + " --holdout 9 --fit-axes 4 --warmup 3 --out " + refused.string());
    EXPECT_EQ(b.exit_code, 2) << b.err;
    EXPECT_NE(b.err.find("--holdout 9: "), std::string::npos) << b.err;
    EXPECT_NE(b.err.find("no frame is held out"), std::string::npos) << b.err;
    EXPECT_FALSE(fs::exists(refused));
}

// mpirun -np R: the fits are shared over the ranks as kdop optimize shares them, and rank 0 measures
// and writes; the files are those of a run without mpirun (the fitted sets, the manifest, every
// figure but the timed ms), printed once. A usage error is one, exit 2, before any work.
TEST(CliChoose, TheSameFilesOnAnyRankCount) {
#ifndef KDOP_MPIEXEC
    GTEST_SKIP() << "kdop was built without MPI (libopenmpi-dev)";
#else
    test::TempDir dir;
    const fs::path scenes = dir / "scenes";
    auto s = test::run(test::kdop_binary() + " scene --scenes grass asphalt --size 40x24 --frames 10 --out " +
                       scenes.string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    auto choose = [&](const std::string& launch, const fs::path& out, const std::string& validate) {
        return test::run(launch + test::kdop_binary() + " choose --fit " + (scenes / "grass-ghosting").string() +
                         validate + " --fit-axes 4 5 --sets aabb --warmup 3 --sample 1500 --timing-rounds 2 " +
                         "--no-charts --out " + out.string());
    };
    const std::string validate = " --validate " + (scenes / "asphalt-ghosting").string();
    auto alone = choose("", dir / "alone", validate);
    ASSERT_EQ(alone.exit_code, 0) << alone.err;
    // Every column but the timed ones.
    auto figures = [](const fs::path& csv) {
        auto rows = test::csv_rows(test::read_file(csv));
        for (auto& row : rows) row.erase("ms"), row.erase("ms_q1"), row.erase("ms_q3");
        return rows;
    };
    for (int ranks : {2, 3}) {
        SCOPED_TRACE(fmt::format("{} ranks", ranks));
        const fs::path out = dir / fmt::format("ranks{}", ranks);
        auto r = choose(test::mpirun_np() + std::to_string(ranks) + " ", out, validate);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        for (const char* file : {"fitted4.axes", "fitted5.axes", "kdop.manifest"})
            EXPECT_EQ(test::read_file(out / file), test::read_file(dir / "alone" / file)) << file;
        EXPECT_EQ(figures(out / "candidates.csv"), figures(dir / "alone" / "candidates.csv"));
        EXPECT_EQ(figures(out / "candidates.csv").size(), 3u);
        std::size_t printed = 0;
        for (std::size_t at = 0; (at = r.out.find("kdop choose: ", at)) != std::string::npos; ++at) ++printed;
        EXPECT_EQ(printed, 1u) << r.out;
        EXPECT_NE(r.err.find(fmt::format("on rank 0 of {}", ranks)), std::string::npos) << r.err;
    }
    const fs::path refused = dir / "refused";
    auto b = choose(test::mpirun_np() + "2 ", refused, "");
    EXPECT_EQ(b.exit_code, 2) << b.err;
    EXPECT_NE(b.err.find("give --validate SEQUENCE... or --holdout FRAMES"), std::string::npos) << b.err;
    EXPECT_EQ(b.err.find("give --validate"), b.err.rfind("give --validate")) << "one rank speaks\n" << b.err;
    EXPECT_FALSE(fs::exists(refused));
#endif
}

// --lavapipe-cost: each clip candidate's instructions per pixel beyond the gather, counted by
// callgrind (more slabs, more instructions); a varclip candidate has no such count and is left empty.
TEST(ChooseCallgrind, CountsEachClipCandidatesLavapipeInstructions) {
    test::TempDir dir;
    auto kdop = [](const std::string& args) { return test::run(test::kdop_binary() + " " + args); };
    const fs::path scenes = dir / "scenes", out = dir / "choose";
    auto s = kdop("scene --scenes grass asphalt --size 32x24 --frames 6 --out " + scenes.string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    auto r = kdop("choose --fit " + (scenes / "grass-ghosting").string() + " --validate " +
                  (scenes / "asphalt-ghosting").string() +
                  " --fit-axes 4 --sets aabb dop22 --modes clip varclip --warmup 2 --sample 500 --timing-rounds 2 "
                  "--no-charts --lavapipe-cost --out " +
                  out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::map<std::string, std::string> counted;
    for (auto c : test::csv_rows(test::read_file(out / "candidates.csv"))) counted[c["variant"]] = c["lavapipe_instr"];
    ASSERT_EQ(counted.size(), 6u);
    for (const char* clip : {"fitted4-clip-n9", "aabb-clip-n9", "dop22-clip-n9"}) {
        ASSERT_FALSE(counted[clip].empty()) << clip;
        EXPECT_GT(std::stod(counted[clip]), 0.0) << clip;
    }
    EXPECT_GT(std::stod(counted["dop22-clip-n9"]), std::stod(counted["aabb-clip-n9"])) << "11 slabs against 3";
    for (const char* varclip : {"fitted4-varclip-n9", "aabb-varclip-n9", "dop22-varclip-n9"})
        EXPECT_TRUE(counted[varclip].empty()) << varclip;
}

} // namespace
} // namespace kdop
