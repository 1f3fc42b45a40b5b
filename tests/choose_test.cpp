// kdop choose (optimize/choose.h): the recommendation rule on constructed candidates whose answer
// is known, the manifest it writes, and the command's held-out figures against kdop taa's.
#include "generator/manifest.h"
#include "harness/block_bootstrap.h"
#include "harness/statistics.h"
#include "images/random.h"
#include "optimize/choice_chart.h"
#include "optimize/choice_report.h"
#include "optimize/choose.h"
#include "test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <set>
#include <sstream>

namespace kdop {
namespace {

namespace fs = std::filesystem;

double mean_of_frames(const std::vector<double>& frames) {
    double sum = 0;
    for (double v : frames) sum += v;
    return sum / double(frames.size());
}

// What kdop.manifest opens with, the default resolve's settings written after the comment.
const std::string kManifestHead =
    "# kdop choose's recommendation (choice.md says why), and the TAA resolve it was measured\n"
    "# with: build the resolve with these (kdop_add_variants declares them as resolve_settings).\n"
    "gamma: 1\ncurrent-weight: 0.1\ncolor-map: linear\nhistory-filter: bilinear\ndilate-motion: no\n";

Candidate candidate(const std::string& set, bool fitted, std::size_t ops, double held_out, double fit = NAN) {
    Candidate c;
    c.ms = double(ops) / 100; // a time that follows the float ops, for the ms budget
    c.key = {set, Mode::clip, Neighborhood::n9};
    c.fitted = fitted;
    c.float_ops = ops;
    c.figures.resize(kBuiltinMetrics);
    c.figures[kGhosting].held_out = held_out;
    c.figures[kGhosting].fit = fit;
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
    EXPECT_EQ(choice_manifest(result, {}), kManifestHead + "dop16-grass-clip-n9\n");
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

// The block bootstrap as documented (harness/block_bootstrap.h), computed here on known per-frame
// figures: SplitMix64 from the seed, replicate by replicate, sequence by sequence, block by block,
// next() % blocks; the figure the mean over sequences of each one's mean of the frames drawn.
std::vector<std::vector<double>> bootstrap_here(const std::vector<std::vector<std::vector<double>>>& figures,
                                                std::size_t block, std::size_t replicates, std::uint64_t seed) {
    std::vector<std::vector<double>> out(figures.size(), std::vector<double>(replicates, 0.0));
    Random random(seed);
    for (std::size_t r = 0; r < replicates; ++r)
        for (std::size_t s = 0; s < figures[0].size(); ++s) {
            const std::size_t n = figures[0][s].size(), blocks = (n + block - 1) / block;
            std::vector<std::size_t> starts;
            for (std::size_t b = 0; b < blocks; ++b) starts.push_back(block * (random.next() % blocks));
            for (std::size_t c = 0; c < figures.size(); ++c) {
                std::vector<double> drawn;
                for (std::size_t start : starts)
                    for (std::size_t f = start; f < std::min(start + block, n); ++f) drawn.push_back(figures[c][s][f]);
                double sum = 0;
                for (double v : drawn) sum += v;
                out[c][r] += sum / double(drawn.size()) / double(figures[0].size());
            }
        }
    return out;
}

// Known per-frame figures: two sequences of 23 and 17 frames (blocks of 5, the last ones short),
// two candidates. Each candidate's interval is the bootstrap computed above, to the last bit of its
// order statistics; the second candidate is the first plus 0.001 on every frame, so their paired
// difference is 0.001 in every replicate (beyond noise) though their own intervals overlap, and a
// third that differs frame by frame in both directions is within noise of the first.
TEST(Choose, HeldOutIntervalsAreABlockBootstrapOfTheFrames) {
    Random content(42);
    std::vector<std::vector<double>> first(2);
    for (std::size_t f = 0; f < 23; ++f) first[0].push_back(0.02 + 0.01 * content.uniform() + 0.0005 * double(f % 7));
    for (std::size_t f = 0; f < 17; ++f) first[1].push_back(0.03 + 0.02 * content.uniform());
    auto second = first, third = first;
    for (auto& sequence : second)
        for (double& v : sequence) v += 0.001;
    for (auto& sequence : third)
        for (std::size_t f = 0; f < sequence.size(); ++f) sequence[f] += f % 2 ? 0.004 : -0.004;
    const std::vector<std::vector<std::vector<double>>> figures{first, second, third};
    const BootstrapOptions options{5, 999, 7, 0.9};
    auto drawn = bootstrap_replicates(figures, options);
    ASSERT_TRUE(drawn);
    const auto here = bootstrap_here(figures, 5, 999, 7);
    for (std::size_t c = 0; c < 3; ++c) {
        SCOPED_TRACE(c);
        ASSERT_EQ((*drawn)[c].size(), 999u);
        for (std::size_t r = 0; r < 999; ++r) ASSERT_NEAR((*drawn)[c][r], here[c][r], 1e-15) << r;
        std::vector<double> sorted = here[c];
        std::sort(sorted.begin(), sorted.end());
        const Interval interval = percentile_interval((*drawn)[c], 0.9);
        EXPECT_NEAR(interval.low, quantile_of_sorted(sorted, 0.05), 1e-15);
        EXPECT_NEAR(interval.high, quantile_of_sorted(sorted, 0.95), 1e-15);
        // The figure itself, the mean of the sequences' means, lies inside; the interval is not a point.
        const double figure = (mean_of_frames(figures[c][0]) + mean_of_frames(figures[c][1])) / 2;
        EXPECT_TRUE(interval.holds(figure)) << figure;
        EXPECT_GT(interval.high - interval.low, 0.001);
    }
    EXPECT_NEAR(difference_interval((*drawn)[1], (*drawn)[0], 0.9).low, 0.001, 1e-12);
    EXPECT_FALSE(difference_interval((*drawn)[1], (*drawn)[0], 0.9).holds(0)) << "paired: beyond noise";
    EXPECT_TRUE(percentile_interval((*drawn)[1], 0.9).low < percentile_interval((*drawn)[0], 0.9).high)
        << "though their own intervals overlap";
    EXPECT_TRUE(difference_interval((*drawn)[2], (*drawn)[0], 0.9).holds(0));

    // Seeded: the same seed, the same replicates; another seed, others. Too few frames: none.
    EXPECT_EQ(*bootstrap_replicates(figures, options), *drawn);
    EXPECT_NE(*bootstrap_replicates(figures, {5, 999, 8, 0.9}), *drawn);
    EXPECT_FALSE(bootstrap_replicates(figures, {9, 999, 7, 0.9})) << "17 frames are not two blocks of 9";
    EXPECT_FALSE(bootstrap_replicates({first, {first[0]}}, options)) << "candidates not on the same frames";
    // The block a resolve's history asks for: ceil(1 / w).
    EXPECT_EQ(history_block(0.1f), 10u);
    EXPECT_EQ(history_block(0.3f), 4u);
    EXPECT_EQ(history_block(1.0f), 1u);
}

// The recommendation says when the runner-up is within noise of it (the paired interval holds 0)
// and when it is not, and the table marks every candidate's ghosting_noise against it.
TEST(Choose, TheRecommendationSaysWhenTheRunnerUpIsWithinNoise) {
    std::vector<Candidate> candidates{candidate("a", false, 100, 0.0094), candidate("b", false, 120, 0.0100),
                                      candidate("c", false, 90, 0.0200)};
    // Replicates around each figure: b's difference from a crosses 0 (+-0.001 around +0.0006); c's does not.
    for (std::size_t r = 0; r < 200; ++r) {
        const double wobble = 0.001 * (double(r % 21) - 10) / 10;
        candidates[0].replicates.push_back(0.0094 + wobble);
        candidates[1].replicates.push_back(0.0100 + wobble + (r % 2 ? 0.001 : -0.001));
        candidates[2].replicates.push_back(0.0200 + wobble);
    }
    for (Candidate& c : candidates) c.interval = percentile_interval(c.replicates, 0.95);
    const Recommendation all = recommend(candidates, {}, std::nullopt);
    ASSERT_EQ(all.chosen, 0u);
    EXPECT_EQ(all.runner_up, 1u);
    EXPECT_TRUE(all.difference.holds(0));
    EXPECT_NE(all.noise.find("The runner-up, b-clip-n9, ghosts 0.0100, within noise of it"), std::string::npos)
        << all.noise;
    // Within 110 float ops, the runner-up is c, beyond noise.
    const Recommendation cheap = recommend(candidates, {.ops = 110}, std::nullopt);
    ASSERT_EQ(cheap.chosen, 0u);
    EXPECT_EQ(cheap.runner_up, 2u);
    EXPECT_NE(cheap.noise.find("The runner-up, c-clip-n9, ghosts 0.0200, beyond noise"), std::string::npos)
        << cheap.noise;
    // A target the chosen one's interval reaches above is said to be at risk.
    const Recommendation target = recommend(candidates, {}, 0.0097);
    ASSERT_EQ(target.chosen, 0u);
    EXPECT_NE(target.noise.find("reaches above the target 0.0097"), std::string::npos) << target.noise;

    // choice.md says it as recommend() does, in plain words (no escaped emphasis).
    ChooseResult result;
    result.candidates = candidates, result.recommendation = all;
    const std::string md = choice_markdown(result, {}, {});
    EXPECT_NE(md.find("The runner-up, b-clip-n9, ghosts 0.0100, within noise of it"), std::string::npos) << md;
    EXPECT_EQ(md.find("\\*"), std::string::npos) << md;

    mark_noise(candidates, all);
    EXPECT_EQ(candidates[0].within_noise, true);
    EXPECT_EQ(candidates[1].within_noise, true);
    EXPECT_EQ(candidates[2].within_noise, false);
    const auto rows = test::csv_rows(candidates_table(candidates, default_metrics()).csv());
    EXPECT_EQ(rows[1].at("ghosting_noise"), "1");
    EXPECT_EQ(rows[2].at("ghosting_noise"), "0");
    EXPECT_FALSE(rows[2].at("validation_ghosting_low").empty());

    // Without replicates (too few frames) nothing is said to be within noise, and the report says why.
    std::vector<Candidate> bare{candidate("a", false, 100, 0.0094), candidate("b", false, 120, 0.0100)};
    const Recommendation none = recommend(bare, {}, std::nullopt);
    EXPECT_NE(none.noise.find("too few for an interval"), std::string::npos) << none.noise;
    mark_noise(bare, none);
    EXPECT_FALSE(bare[1].within_noise);
}

// choice.png draws the budget: a line at --budget-ops or at --target-ghosting, across the
// candidates' span and in the plot's data so that a budget beyond every candidate is still on the
// chart; the candidates over a --budget-ms crossed out; the held-out ghosting with its interval.
TEST(Choose, TheChartDrawsTheBudget) {
    ChooseResult result;
    result.candidates = {candidate("aabb", false, 93, 0.03), candidate("dop22", false, 381, 0.02)};
    for (Candidate& c : result.candidates) c.interval = {c.ranked() - 0.001, c.ranked() + 0.001};
    result.recommendation = recommend(result.candidates, {.ops = 400}, std::nullopt);
    auto file = [](const ChoicePlot& plot, const std::string& name) {
        const auto at = std::ranges::find(plot.data, name, [](const auto& file) { return file.first; });
        return at == plot.data.end() ? std::string("(none)") : at->second;
    };
    ChooseOptions options;
    for (std::size_t budget : {400, 1000}) {
        options.budget_ops = budget;
        const ChoicePlot ops = choice_plot(result, options, "/scratch");
        EXPECT_NE(
            ops.script.find("choice-budget.dat\" using 1:2 with lines dt 2 lw 2 lc rgb '#2ca02c' title 'budget: " +
                            std::to_string(budget) + " float ops'"),
            std::string::npos)
            << ops.script;
        // Vertical, from the least to the most ghosting drawn (the intervals' ends).
        EXPECT_EQ(file(ops, "choice-budget.dat"), fmt::format("{0} 0.019\n{0} 0.031\n", budget));
        EXPECT_NE(ops.script.find("using 1:2:5:6 with yerrorbars"), std::string::npos) << "the intervals";
        EXPECT_NE(ops.script.find("as kdop gen counts them"), std::string::npos);
    }

    options = {};
    options.target_ghosting = 0.025;
    const ChoicePlot target = choice_plot(result, options, "/scratch");
    EXPECT_NE(target.script.find("title 'target: ghosting 0.025'"), std::string::npos) << target.script;
    EXPECT_EQ(file(target, "choice-budget.dat"), "93 0.025\n381 0.025\n") << "horizontal, across the candidates";

    options = {};
    options.budget_ms = 3;
    const ChoicePlot ms = choice_plot(result, options, "/scratch");
    EXPECT_NE(ms.script.find("over the budget of 3 ms"), std::string::npos) << ms.script;
    const std::string over = file(ms, "choice-over.dat");
    EXPECT_NE(over.find("381"), std::string::npos) << "dop22, 3.81 ms, is over:\n" << over;
    EXPECT_EQ(over.find("93"), std::string::npos) << "aabb, 0.93 ms, is not";
    EXPECT_EQ(ms.script.find("choice-budget.dat"), std::string::npos) << "no line for a budget the axes do not have";
}

// kdop.manifest records every setting of the resolve the recommendation was measured with, in lines
// read_manifest reads back as given (before, the engine had to guess gamma = 1), and choice.md
// lists them with the variant's mode and neighborhood and the FLIP mode.
TEST(Choose, TheManifestAndReportRecordTheSettingsMeasuredWith) {
    ChooseOptions options;
    options.evaluation.resolve.gamma = 1.5f;
    options.evaluation.resolve.current_weight = 0.2f;
    options.evaluation.resolve.color_map = *parse_color_map("gamma:2.2");
    options.evaluation.resolve.history_filter = HistoryFilter::catmull_rom;
    options.evaluation.resolve.dilate_motion = true;
    ChooseResult result;
    result.candidates = {candidate("aabb", false, 93, 0.03)};
    result.candidates[0].key.mode = Mode::varclip;
    result.recommendation.chosen = 0;
    result.range = ColorRange::hdr;
    test::TempDir dir;
    test::write_file(dir / "kdop.manifest", choice_manifest(result, options));
    auto read = read_manifest(dir / "kdop.manifest");
    ASSERT_TRUE(read) << read.error().message;
    ASSERT_TRUE(read->resolve);
    // Read back field by field (Manifest.RecordsTheResolveItsVariantsWereMeasuredWith), so its lines say it.
    EXPECT_EQ(resolve_lines(*read->resolve), "gamma: 1.5\ncurrent-weight: 0.2\ncolor-map: gamma:2.2\n"
                                             "history-filter: catmull-rom\ndilate-motion: yes\n");
    EXPECT_EQ(variant_name(read->variants.at(0)), "aabb-varclip-n9");

    const std::string md = choice_markdown(result, options, {});
    for (const char* row : {"| mode (recommended) | varclip |", "| neighborhood (recommended) | n9 |",
                            "| gamma (the variance clip's width; varclip only) | 1.5 |", "| current weight | 0.2 |",
                            "| color map | gamma:2.2 |", "| history filter | catmull-rom |",
                            "| motion dilation | yes |", "| FLIP | HDR-FLIP at"})
        EXPECT_NE(md.find(row), std::string::npos) << row << "\n" << md;
    EXPECT_NE(md.find("**Every ghosting and shimmer here is HDR-FLIP**"), std::string::npos) << md;
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
    const std::string manifest = choice_manifest(result, {});
    EXPECT_EQ(manifest, kManifestHead + "set: fitted4.axes\nfitted4-clip-n9\n");
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
    const std::string manifest = kManifestHead + "set: mine.axes\nmine-clip-n9\n";
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

// Each variant's printed row of `kdop gen`: its float_ops column, by variant.
std::map<std::string, std::string> gen_float_ops(const std::string& printed) {
    std::map<std::string, std::string> ops;
    std::istringstream lines(printed);
    std::string name, k, bytes, instructions, code, float_ops;
    for (std::string line; std::getline(lines, line);) {
        std::istringstream fields(line);
        // A variant's name has a dash; the header and the closing "wrote ..." line do not.
        if (fields >> name >> k >> bytes >> instructions >> code >> float_ops && name.find('-') != std::string::npos)
            ops[name] = float_ops;
    }
    return ops;
}

// The held-out figures are kdop taa's on the held-out sequences, to the last digit (the same
// evaluation), for the fitted set as for the built-in ones, in both modes by default. Each interval
// is the block bootstrap of taa's per-frame figures, computed here (blocks of ceil(1 / w) = 2 frames
// at --current-weight 0.5, 2000 replicates, the default seed 1), and each ghosting_noise flag the
// paired difference from the recommended candidate holding 0. Float ops are kdop gen's count (they
// were the analytic bound: aabb-clip-n9 87 in choose, 93 in kdop gen), and a --budget-ops at the
// bound of the cheapest candidate admits none. Without held-out sequences, or with a sequence both
// fitted to and held out, the command line is refused and nothing is written.
TEST(CliChoose, HeldOutFiguresAreKdopTaasOnTheHeldOutSequences) {
    test::TempDir dir;
    auto kdop = [](const std::string& args) { return test::run(test::kdop_binary() + " " + args); };
    const fs::path scenes = dir / "scenes", out = dir / "choose", taa = dir / "taa";
    auto s = kdop("scene --scenes grass asphalt --size 48x32 --frames 12 --out " + scenes.string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const std::string fit = (scenes / "grass-ghosting").string(), held = (scenes / "asphalt-ghosting").string();
    auto r =
        kdop("choose --fit " + fit + " --validate " + held +
             " --fit-axes 4 --sets aabb dop22 --warmup 3 --current-weight 0.5 --sample 2000 --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* file :
         {"candidates.csv", "candidates.json", "choice.md", "choice.png", "fitted4.axes", "kdop.manifest"})
        EXPECT_TRUE(fs::exists(out / file)) << file;
    const std::string md = test::read_file(out / "choice.md");
    EXPECT_NE(md.find("](choice.png)"), std::string::npos);
    EXPECT_NE(md.find("blocks of 2 consecutive frames"), std::string::npos) << md;
    EXPECT_NE(md.find("2000 replicates draw as many blocks with replacement (seed 1, `--seed`)"), std::string::npos)
        << md;
    EXPECT_NE(md.find("**Every ghosting and shimmer here is LDR-FLIP**"), std::string::npos) << md;
    auto t =
        kdop("taa --sequence " + held + " --sets aabb dop22 " + (out / "fitted4.axes").string() +
             " --warmup 3 --current-weight 0.5 --timing-rounds 2 --no-charts --viewer-frames 0 --out " + taa.string());
    ASSERT_EQ(t.exit_code, 0) << t.err;
    const auto candidates = test::csv_rows(test::read_file(out / "candidates.csv"));
    const auto rows = test::csv_rows(test::read_file(taa / "taa.csv"));
    const auto frames = test::csv_rows(test::read_file(taa / "taa_frames.csv"));
    ASSERT_EQ(candidates.size(), 6u) << "3 sets in clip and varclip";
    auto gen = kdop("gen --sets aabb dop22 " + (out / "fitted4.axes").string() + " --out " + (dir / "gen").string());
    ASSERT_EQ(gen.exit_code, 0) << gen.err;
    const auto generated = gen_float_ops(gen.out);
    // Each candidate's per-frame ghosting, as kdop taa measured it, for the bootstrap.
    std::vector<std::vector<std::vector<double>>> per_frame;
    for (auto c : candidates) {
        SCOPED_TRACE(c["variant"]);
        EXPECT_EQ(c["fitted"], c["variant"].starts_with("fitted4-") ? "1" : "0");
        auto row = std::find_if(rows.begin(), rows.end(), [&](auto& row) { return row.at("variant") == c["variant"]; });
        ASSERT_NE(row, rows.end());
        EXPECT_EQ(c["validation_ghosting"], row->at("ghosting"));
        EXPECT_EQ(c["validation_ghosting_median"], row->at("ghosting_median"));
        EXPECT_EQ(c["validation_ghosting_p95"], row->at("ghosting_p95"));
        EXPECT_FALSE(c["fit_ghosting"].empty());
        EXPECT_EQ(c["flip"], "LDR-FLIP");
        ASSERT_TRUE(generated.count(c["variant"])) << gen.out;
        EXPECT_EQ(c["float_ops"], generated.at(c["variant"]));
        EXPECT_LE(std::stoi(c["analytic_min_ops"]), std::stoi(c["float_ops"]));
        per_frame.push_back({{}});
        for (auto f : frames)
            if (f["variant"] == c["variant"]) per_frame.back()[0].push_back(std::stod(f["ghosting"]));
        ASSERT_EQ(per_frame.back()[0].size(), 9u);
    }
    const auto replicates = bootstrap_here(per_frame, 2, 2000, 1);
    const std::string manifest = test::read_file(out / "kdop.manifest");
    const std::string chosen = manifest.substr(manifest.rfind('\n', manifest.size() - 2) + 1);
    const auto recommended =
        std::ranges::find_if(candidates, [&](auto& c) { return c.at("variant") + "\n" == chosen; });
    ASSERT_NE(recommended, candidates.end()) << manifest;
    const std::size_t best = std::size_t(recommended - candidates.begin());
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        auto c = candidates[i];
        SCOPED_TRACE(c["variant"]);
        std::vector<double> sorted = replicates[i], difference(replicates[i].size());
        std::sort(sorted.begin(), sorted.end());
        EXPECT_NEAR(std::stod(c["validation_ghosting_low"]), quantile_of_sorted(sorted, 0.025), 1e-12);
        EXPECT_NEAR(std::stod(c["validation_ghosting_high"]), quantile_of_sorted(sorted, 0.975), 1e-12);
        for (std::size_t k = 0; k < difference.size(); ++k) difference[k] = replicates[i][k] - replicates[best][k];
        std::sort(difference.begin(), difference.end());
        const bool within = quantile_of_sorted(difference, 0.025) <= 0 && 0 <= quantile_of_sorted(difference, 0.975);
        EXPECT_EQ(c["ghosting_noise"], within ? "1" : "0");
        // kdop taa gives the same interval (the same frames, blocks and seed), and, the recommended
        // candidate being the least ghosting here, the same noise flag.
        auto row = std::find_if(rows.begin(), rows.end(), [&](auto& row) { return row.at("variant") == c["variant"]; });
        EXPECT_EQ(row->at("ghosting_low"), c["validation_ghosting_low"]);
        EXPECT_EQ(row->at("ghosting_high"), c["validation_ghosting_high"]);
        EXPECT_EQ(row->at("ghosting_noise"), c["ghosting_noise"]);
    }
    // The manifest selects exactly the recommended variant, the one choose printed.
    EXPECT_NE(r.out.find("kdop choose: " + chosen.substr(0, chosen.size() - 1) + ":"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Its held-out ghosting's 95% interval is ["), std::string::npos) << r.out;

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
    // --budget-ops is held against the generator's count: at aabb-clip-n9's analytic bound, below its
    // count, nothing qualifies (the analytic bound admitted it).
    std::map<std::string, std::map<std::string, std::string>> by_name;
    for (auto c : candidates) by_name[c["variant"]] = c;
    const std::string bound = by_name["aabb-clip-n9"]["analytic_min_ops"];
    ASSERT_LT(std::stoi(bound), std::stoi(by_name["aabb-clip-n9"]["float_ops"]));
    ASSERT_LT(std::stoi(bound), std::stoi(by_name["fitted4-clip-n9"]["float_ops"]));
    auto ops = kdop("choose --fit " + fit + " --validate " + held +
                    " --fit-axes 4 --sets aabb --modes clip --warmup 3 --sample 2000 --timing-rounds 2 --no-charts "
                    "--budget-ops " +
                    bound + " --out " + (dir / "ops").string());
    ASSERT_EQ(ops.exit_code, 0) << ops.err;
    EXPECT_NE(ops.out.find("no recommendation: no candidate's clip costs at most " + bound + " float ops"),
              std::string::npos)
        << ops.out;

    for (const std::string& bad : {std::string("--fit ") + fit, "--fit " + fit + " --validate " + fit}) {
        const fs::path refused = dir / "refused";
        auto b = kdop("choose " + bad + " --fit-axes 4 --warmup 3 --out " + refused.string());
        EXPECT_EQ(b.exit_code, 2) << bad << "\n" << b.err;
        EXPECT_NE(b.err.find("--validate"), std::string::npos) << b.err;
        EXPECT_FALSE(fs::exists(refused)) << bad;
    }
}

// `dir`'s sequence copied to `copy` as an HDR one ("color": {"range": "hdr"}): measured in HDR-FLIP.
void copy_as_hdr(const fs::path& dir, const fs::path& copy) {
    fs::copy(dir, copy, fs::copy_options::recursive);
    auto json = nlohmann::json::parse(test::read_file(copy / "sequence.json"));
    json["color"] = {{"range", "hdr"}};
    test::write_file(copy / "sequence.json", json.dump(2));
}

// Fit frames in LDR-FLIP beside held-out ones in HDR-FLIP read as overfitting (0.0095 against
// 0.0239 on a team's frames): sequences of two color ranges are a wrong command line, exit 2,
// before the fit, naming both and their FLIP modes. Sequences of one range are measured in its
// mode, which choice.md and every row of candidates.csv name. Without --modes and
// --neighborhoods, choose measures what kdop gen generates and kdop taa measures: both modes, n9.
TEST(CliChoose, EveryFigureIsInOneFlipModeAndTheDefaultSelectionIsGensAndTaas) {
    test::TempDir dir;
    auto kdop = [](const std::string& args) { return test::run(test::kdop_binary() + " " + args); };
    const fs::path scenes = dir / "scenes";
    auto s = kdop("scene --scenes grass asphalt --size 32x24 --frames 8 --out " + scenes.string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const fs::path grass = scenes / "grass-ghosting", asphalt = scenes / "asphalt-ghosting";
    copy_as_hdr(grass, dir / "grass-hdr");
    copy_as_hdr(asphalt, dir / "asphalt-hdr");
    const std::string choose = "choose --fit-axes 3 --sets aabb --warmup 2 --sample 500 --timing-rounds 2 --no-charts ";
    const fs::path refused = dir / "refused";
    for (const std::string& mixed : {"--fit " + grass.string() + " --validate " + (dir / "asphalt-hdr").string(),
                                     "--fit " + (dir / "grass-hdr").string() + " --validate " + asphalt.string(),
                                     "--fit " + grass.string() + " " + (dir / "grass-hdr").string() + " --holdout 2"}) {
        auto r = kdop(choose + mixed + " --out " + refused.string());
        EXPECT_EQ(r.exit_code, 2) << mixed << "\n" << r.err;
        EXPECT_NE(r.err.find("HDR, measured in HDR-FLIP"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("LDR, measured in LDR-FLIP"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("give sequences of one range"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("fitting"), std::string::npos) << "before the fit\n" << r.err;
        EXPECT_FALSE(fs::exists(refused));
    }

    const fs::path out = dir / "hdr";
    auto r = kdop(choose + "--fit " + (dir / "grass-hdr").string() + " --validate " + (dir / "asphalt-hdr").string() +
                  " --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::set<std::string> variants;
    for (auto c : test::csv_rows(test::read_file(out / "candidates.csv"))) {
        EXPECT_EQ(c["flip"], "HDR-FLIP") << c["variant"];
        variants.insert(c["variant"]);
    }
    EXPECT_EQ(variants,
              (std::set<std::string>{"fitted3-clip-n9", "fitted3-varclip-n9", "aabb-clip-n9", "aabb-varclip-n9"}));
    const std::string md = test::read_file(out / "choice.md");
    EXPECT_NE(md.find("**Every ghosting and shimmer here is HDR-FLIP**"), std::string::npos) << md;
    EXPECT_NE(md.find("| FLIP | HDR-FLIP at"), std::string::npos) << md;
    const std::string json = test::read_file(out / "candidates.json");
    EXPECT_NE(json.find("\"HDR-FLIP\""), std::string::npos) << "the figures' unit";

    // The same default in kdop gen and kdop taa, and in every command's help.
    auto gen = kdop("gen --sets aabb --out " + (dir / "gen").string());
    ASSERT_EQ(gen.exit_code, 0) << gen.err;
    EXPECT_EQ(gen_float_ops(gen.out).size(), 2u) << gen.out;
    EXPECT_TRUE(fs::exists(dir / "gen" / "aabb-varclip-n9.spv"));
    EXPECT_FALSE(fs::exists(dir / "gen" / "aabb-clip-n5.spv"));
    auto taa = kdop("taa --sequence " + asphalt.string() +
                    " --sets aabb --warmup 2 --timing-rounds 1 --no-charts "
                    "--viewer-frames 0 --out " +
                    (dir / "taa").string());
    ASSERT_EQ(taa.exit_code, 0) << taa.err;
    std::set<std::string> measured;
    for (auto row : test::csv_rows(test::read_file(dir / "taa" / "taa.csv"))) measured.insert(row["variant"]);
    EXPECT_EQ(measured, (std::set<std::string>{"aabb-clip-n9", "aabb-varclip-n9"}));
    for (const char* command : {"gen", "taa", "choose"}) {
        auto help = kdop(std::string(command) + " --help");
        EXPECT_NE(help.out.find("[default: clip varclip"), std::string::npos) << command << "\n" << help.out;
        EXPECT_NE(help.out.find("[default: n9"), std::string::npos) << command << "\n" << help.out;
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
                  " --warmup 3 --timing-rounds 2 --no-charts --viewer-frames 0 --out " + taa.string());
    ASSERT_EQ(t.exit_code, 0) << t.err;
    const auto frames = test::csv_rows(test::read_file(taa / "taa_frames.csv"));
    const auto candidates = test::csv_rows(test::read_file(out / "candidates.csv"));
    ASSERT_EQ(candidates.size(), 4u) << "2 sets in clip and varclip";
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

// Sequences drawn for upscaling (kdop scene --upscale 2): the sets are fitted to the input-size
// frames, the neighborhoods the upscaling resolve clips against, and every held-out figure is kdop
// taa's on the same sequence, through the same upscaling resolve, to the digit.
TEST(CliChoose, UpscaledSequencesAreJudgedThroughTheUpscalingResolve) {
    test::TempDir dir;
    auto kdop = [](const std::string& args) { return test::run(test::kdop_binary() + " " + args); };
    const fs::path scenes = dir / "scenes", out = dir / "choose", taa = dir / "taa";
    auto s = kdop("scene --scenes grass3d asphalt3d --size 64x36 --frames 10 --upscale 2 --reference-samples 4 --out " +
                  scenes.string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const std::string fit = (scenes / "grass3d-ghosting").string(), validate = (scenes / "asphalt3d-ghosting").string();
    auto r =
        kdop("choose --fit " + fit + " --validate " + validate +
             " --fit-axes 4 --sets aabb --modes clip --warmup 4 --timing-rounds 2 --no-charts --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(test::read_file(out / "fitted4.axes").find("5760 3x3 neighborhoods"), std::string::npos)
        << "fitted to the 32x18 input frames (10 x 576 neighborhoods):\n"
        << test::read_file(out / "fitted4.axes");
    auto t = kdop("taa --sequence " + validate + " --sets aabb " + (out / "fitted4.axes").string() +
                  " --modes clip --warmup 4 --timing-rounds 2 --no-charts --viewer-frames 0 --out " + taa.string());
    ASSERT_EQ(t.exit_code, 0) << t.err;
    const auto rows = test::csv_rows(test::read_file(taa / "taa.csv"));
    const auto candidates = test::csv_rows(test::read_file(out / "candidates.csv"));
    ASSERT_EQ(candidates.size(), 2u);
    for (auto c : candidates) {
        SCOPED_TRACE(c["variant"]);
        const auto row = std::ranges::find_if(rows, [&](auto& r) { return r.at("variant") == c["variant"]; });
        ASSERT_NE(row, rows.end());
        EXPECT_EQ(c["validation_ghosting"], row->at("ghosting"));
        EXPECT_EQ(row->at("ghosting_against"), "reference");
    }
    // The manifest records how the resolve upscaled, and a manifest read back gives those lines.
    const std::string manifest = test::read_file(out / "kdop.manifest");
    EXPECT_NE(manifest.find("upscale-filter: lanczos2\nupscale-sample-distance: all\nupscale-box-scale: none\n"),
              std::string::npos)
        << manifest;
    EXPECT_NE(test::read_file(out / "choice.md").find("The resolve upscaled the sequences' frames"), std::string::npos);
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
        for (auto& row : rows) row.erase("ms"), row.erase("ms_q1"), row.erase("ms_q3"), row.erase("ms_noise");
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
        EXPECT_EQ(figures(out / "candidates.csv").size(), 6u);
        std::size_t printed = 0;
        for (std::size_t at = 0; (at = r.out.find("kdop choose: ", at)) != std::string::npos; ++at) ++printed;
        EXPECT_EQ(printed, 1u) << r.out;
        EXPECT_NE(r.err.find(fmt::format("on rank 0 of {}", ranks)), std::string::npos) << r.err;
        // The candidates' measurements shared: each candidate measured once, by one rank, every rank
        // measuring some, in rank order.
        const std::string report = test::read_file(out / "choice.md");
        const std::size_t line = report.find(fmt::format("The candidates were measured over {} ranks", ranks));
        ASSERT_NE(line, std::string::npos) << report;
        const std::string shares = report.substr(line, report.find('\n', line) - line);
        for (int rank = 0; rank < ranks; ++rank) {
            const std::size_t at = shares.find(fmt::format(" rank {} ", rank));
            ASSERT_NE(at, std::string::npos) << shares;
            EXPECT_NE(shares.substr(at, 12).find("none"), 8u) << shares;
        }
        for (auto c : figures(out / "candidates.csv")) {
            std::size_t seen = 0;
            for (std::size_t at = 0; (at = shares.find(c["variant"], at)) != std::string::npos; ++at) ++seen;
            EXPECT_EQ(seen, 1u) << c["variant"] << " in " << shares;
        }
    }
    EXPECT_EQ(test::read_file(dir / "alone" / "choice.md").find("measured over"), std::string::npos);
    const fs::path refused = dir / "refused";
    auto b = choose(test::mpirun_np() + "2 ", refused, "");
    EXPECT_EQ(b.exit_code, 2) << b.err;
    EXPECT_NE(b.err.find("give --validate SEQUENCE... or --holdout FRAMES"), std::string::npos) << b.err;
    EXPECT_EQ(b.err.find("give --validate"), b.err.rfind("give --validate")) << "one rank speaks\n" << b.err;
    EXPECT_FALSE(fs::exists(refused));

    // A held-out frame that cannot be read, met by the ranks measuring their shares: every rank
    // stops with the frame named, once, and nothing is written.
    fs::copy(scenes / "asphalt-ghosting", dir / "broken", fs::copy_options::recursive);
    const fs::path frame = dir / "broken" / "color" / "0006.exr";
    ASSERT_TRUE(fs::exists(frame));
    fs::resize_file(frame, 100);
    const fs::path stopped = dir / "stopped";
    auto c = choose(test::mpirun_np() + "2 ", stopped, " --validate " + (dir / "broken").string());
    EXPECT_EQ(c.exit_code, 1) << c.err;
    EXPECT_NE(c.err.find("0006.exr"), std::string::npos) << c.err;
    EXPECT_EQ(c.err.find("0006.exr"), c.err.rfind("0006.exr")) << "one rank speaks\n" << c.err;
    EXPECT_FALSE(fs::exists(stopped) && !fs::is_empty(stopped));
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
