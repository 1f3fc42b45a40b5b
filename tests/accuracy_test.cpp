// Accuracy against the ideal clip: the metrics on images small enough to work out by hand, the
// trade table's averaging and Pareto fronts, reading a bench cost.csv, and a whole run on the
// device checked against what must hold (sets with the RGB axes never looser than the RGB AABB).
#include "accuracy/accuracy_charts.h"
#include "accuracy/accuracy_report.h"
#include "accuracy/accuracy_run.h"
#include "accuracy/ideal_clip.h"
#include "accuracy/sampled_distance.h"
#include "images/image_io.h"
#include "reference/cpu_clip.h"
#include "tests/gpu_support.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

namespace kdop {
namespace {

Image row_image(std::initializer_list<glm::vec4> pixels) {
    Image image(static_cast<std::uint32_t>(pixels.size()), 1);
    std::copy(pixels.begin(), pixels.end(), image.pixels.begin());
    return image;
}

TEST(AccuracyMetrics, WorkedOutByHand) {
    // Four pixels, history red everywhere, the ideal clip given:
    // 0: t* = 0 (history outside), the clip returned the history: distance |red - black| = 1, a false accept.
    // 1: t* = 0.5, the clip stopped at t = 0.75 of (0,1,0)->(1,0,0): distance 0.25 sqrt 2.
    // 2: t* = 1 (history inside), returned unchanged: distance 0, not outside.
    // 3: current 4 (so S = 4), t* = 0, clipped exactly at current: distance 0, outside, rejected.
    const glm::vec4 red(1, 0, 0, 1);
    const Image current = row_image({{0, 0, 0, 1}, {0, 1, 0, 1}, {1, 0, 0, 1}, {4, 4, 4, 1}});
    const Image history = row_image({red, red, red, red});
    const Image clipped = row_image({red, {0.75f, 0.25f, 0, 1}, red, {4, 4, 4, 1}});
    const std::vector<double> ideal = {0, 0.5, 1, 0};
    const ClipAccuracy a =
        measure_accuracy(current, history, ideal, clipped, ideal_distances(current, history, ideal, clipped));
    EXPECT_EQ(a.pixels, 4u);
    EXPECT_NEAR(a.mean_dist, (1 + 0.25 * std::sqrt(2.0)) / 4, 1e-7);
    EXPECT_NEAR(a.max_dist, 1.0, 1e-7);
    EXPECT_NEAR(a.p95_dist, 1.0, 1e-7); // nearest rank: the 4th smallest of 4
    EXPECT_EQ(a.outside, 3u);
    EXPECT_EQ(a.falsely_accepted, 1u);
    EXPECT_NEAR(a.false_accept_rate(), 1.0 / 3.0, 1e-12);

    // Distances are in units of S: the same miss at a pixel 4 times as bright counts a quarter.
    const Image bright = row_image({{4, 0, 0, 1}});
    const std::vector<double> d =
        ideal_distances(bright, row_image({{8, 0, 0, 1}}), std::vector<double>{0.5}, row_image({{7, 0, 0, 1}}));
    EXPECT_DOUBLE_EQ(d[0], 1.0 / 4.0);
}

TEST(AccuracyMetrics, CompareDistancesCountsOnlyRealExcess) {
    const std::vector<double> a = {0.5, 0.2 + 1e-7, 0.1, 0.0}, b = {0.25, 0.2, 0.3, 0.0};
    const Looser l = compare_distances(a, b);
    EXPECT_DOUBLE_EQ(l.share, 0.25); // only pixel 0: pixel 1 is a tie within 1e-6
    EXPECT_DOUBLE_EQ(l.largest, 0.25);
}

AccuracyRow row(const std::string& family, const std::string& set, const std::string& n, std::size_t float_ops,
                double mean, std::size_t outside, std::size_t accepted) {
    AccuracyRow r;
    r.key = {set, Mode::clip, *parse_neighborhood(n)};
    r.family = family, r.image = family + "/x", r.float_ops = float_ops, r.k = 6;
    r.gpu.mean_dist = mean, r.gpu.p95_dist = 2 * mean, r.gpu.max_dist = 3 * mean;
    r.gpu.pixels = 100, r.gpu.outside = outside, r.gpu.falsely_accepted = accepted;
    return r;
}

TEST(AccuracyTrade, AveragesPairsAndMarksTheFrontPerNeighborhood) {
    AccuracyRun run;
    // Family f, two pairs each: a (cheap, far), b (costly, close), c (costly and far: dominated).
    for (double scale : {1.0, 3.0}) {
        run.rows.push_back(row("f", "a", "n9", 100, 0.04 * scale, 10, 5));
        run.rows.push_back(row("f", "b", "n9", 300, 0.02 * scale, 10, 1));
        run.rows.push_back(row("f", "c", "n9", 400, 0.05 * scale, 10, 0));
        run.rows.push_back(row("f", "c", "n5", 400, 0.09 * scale, 0, 0)); // alone in n5: on its front
    }
    std::map<VariantKey, LavapipeCost> costs{{*parse_variant_key("a-clip-n9"), {50, NAN}},
                                             {*parse_variant_key("b-clip-n9"), {40, NAN}}};
    const auto trade = trade_rows(run, costs);
    ASSERT_EQ(trade.size(), 4u);
    EXPECT_DOUBLE_EQ(trade[0].mean_dist, 0.08);          // (0.04 + 0.12) / 2
    EXPECT_DOUBLE_EQ(trade[0].max_dist, 0.36);           // the larger max
    EXPECT_DOUBLE_EQ(trade[0].false_accept_rate, 0.5);   // 10 of 20
    EXPECT_TRUE(std::isnan(trade[3].false_accept_rate)); // nothing outside
    EXPECT_TRUE(trade[0].front_float_ops);
    EXPECT_TRUE(trade[1].front_float_ops);
    EXPECT_FALSE(trade[2].front_float_ops);
    EXPECT_TRUE(trade[3].front_float_ops);
    // On lavapipe b is both cheaper and closer, so a leaves the front; c has no cost and no place.
    EXPECT_FALSE(trade[0].front_lavapipe);
    EXPECT_TRUE(trade[1].front_lavapipe);
    EXPECT_FALSE(trade[2].front_lavapipe);
    const std::string csv = trade_table(trade).csv();
    EXPECT_NE(csv.find("f,b-clip-n9,b,clip,n9,6,300,40,,0.04,"), std::string::npos) << csv;
}

TEST(AccuracyTrade, ReadsABenchCostCsvAndNamesTheLineOfBadOnes) {
    test::TempDir dir;
    const auto path = dir / "cost.csv";
    test::write_file(path, "variant,neighborhood,instr_per_px,marginal_ms\naabb-clip-n9,n9,324.5,1.5\n"
                           "dop32-clip-n5,n5,,2.25\ngather-n9,n9,307.25,\ngather-n5,n5,200,\n");
    auto costs = read_bench_costs(path);
    ASSERT_TRUE(costs) << costs.error().message;
    const VariantKey aabb = *parse_variant_key("aabb-clip-n9"), dop32 = *parse_variant_key("dop32-clip-n5");
    EXPECT_DOUBLE_EQ(costs->at(aabb).marginal_instr_per_px, 324.5 - 307.25);
    EXPECT_DOUBLE_EQ(costs->at(aabb).marginal_ms, 1.5);
    EXPECT_TRUE(std::isnan(costs->at(dop32).marginal_instr_per_px)); // not counted
    EXPECT_DOUBLE_EQ(costs->at(dop32).marginal_ms, 2.25);
    EXPECT_FALSE(costs->contains(gather_key(Neighborhood::n9))) << "baselines have no accuracy";

    test::write_file(path, "variant,instr_per_px,marginal_ms\ndop32-clamp-n9,1,1\n");
    auto unnamed = read_bench_costs(path);
    ASSERT_FALSE(unnamed);
    EXPECT_NE(unnamed.error().message.find(path.string() + ":2: 'dop32-clamp-n9' is not a variant name"),
              std::string::npos)
        << unnamed.error().message;

    test::write_file(path, "variant,neighborhood,instr_per_px,marginal_ms\naabb-clip-n9,n9,lots,1\n");
    auto bad = read_bench_costs(path);
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message.find(path.string() + ":2: instr_per_px is 'lots'"), std::string::npos)
        << bad.error().message;
    test::write_file(path, "variant,k\n");
    bad = read_bench_costs(path);
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message.find(":1: not a kdop bench cost.csv"), std::string::npos) << bad.error().message;
}

// Two frames with one file name in different folders stay two families, not one merged row.
TEST(AccuracyInputs, ImagesThatShareAFileNameStayApart) {
    test::TempDir dir;
    std::filesystem::create_directories(dir / "a");
    std::filesystem::create_directories(dir / "b");
    const std::string a = (dir / "a" / "frame.exr").string(), b = (dir / "b" / "frame.exr").string(),
                      c = (dir / "other.exr").string();
    for (const std::string& path : {a, b, c}) ASSERT_TRUE(write_image(path, Image(4, 4, {0.5f, 0.25f, 0.125f, 1})));
    auto pairs = image_pairs({a, b, c});
    ASSERT_TRUE(pairs) << pairs.error().message;
    std::set<std::string> families;
    for (const AccuracyPair& p : *pairs) families.insert(p.family);
    EXPECT_EQ(families, (std::set<std::string>{a, b, "other"}));
    auto twice = image_pairs({a, a});
    ASSERT_FALSE(twice);
    EXPECT_EQ(twice.error().message, "--images: " + a + " is given twice");
}

TEST(AccuracyRun, OnTheDeviceAgreesWithTheReferenceAndKeepsTheAabbBound) {
    AccuracyOptions options;
    auto specs = select_variants({"aabb", "ycocg", "dop22", "dop32"}, {}, {"n9"}, {});
    ASSERT_TRUE(specs) << specs.error().message;
    options.variants = keys_of(*specs);
    options.volume_samples = 8;
    const auto pairs = builtin_pairs(16, 16, 5);
    auto run = run_accuracy(test::runner(), test::catalog(), options, pairs);
    ASSERT_TRUE(run) << run.error().message;
    ASSERT_EQ(run->rows.size(), pairs.size() * options.variants.size());
    std::size_t outside = 0;
    for (const AccuracyRow& r : run->rows) {
        SCOPED_TRACE(r.key.name() + " on " + r.image);
        outside += r.gpu.outside;
        // The device computes the same clips as the reference, up to float32 rounding.
        EXPECT_EQ(r.gpu.outside, r.reference.outside);
        EXPECT_NEAR(r.gpu.mean_dist, r.reference.mean_dist, 1e-3 * std::max(1.0, r.reference.mean_dist));
        if (r.family != "hdr" && r.family != "highlights") { // float32 rounds HDR values coarser
            EXPECT_LT(r.gpu_reference_max, 1e-4);
        }
        // A clip k-DOP contains the hull: its volume is never below the hull's.
        if (r.key.mode == Mode::clip && r.volume.pixels) {
            EXPECT_GE(r.volume.median, 1.0 - 1e-9);
        }
        // Sets that contain X, Y and Z lie inside the RGB AABB: never looser, exactly.
        EXPECT_EQ(r.rgb_axes, r.key.set == "aabb" || r.key.set == "dop22" || r.key.set == "dop32");
        if (r.rgb_axes && r.key.mode == Mode::clip) {
            EXPECT_EQ(r.reference_vs_aabb.share, 0.0);
        }
    }
    EXPECT_GT(outside, 1000u) << "the content must give the clips something to do";
}

// kdop optimize's sampled measure: with every pixel sampled it equals the full measure taken the
// way `kdop accuracy` takes it for the reference (ideal exits of the whole image, the reference's
// rectified image, ideal_distances), up to the float32 the rectified image is stored in.
TEST(SampledDistance, EveryPixelSampledIsTheFullReferenceMeasure) {
    const auto all_pairs = builtin_pairs(16, 16, 5);
    const std::vector<AccuracyPair> pairs(all_pairs.begin(), all_pairs.begin() + 3);
    const std::vector<std::string> names = {"aabb", "dop32"};
    std::vector<std::vector<glm::dvec3>> sets;
    for (const std::string& name : names) sets.push_back(unit_axes(*resolve_axis_set(name)));

    auto sampled = sampled_ideal_distances(pairs, sets, Neighborhood::n9, 1000, 7);
    ASSERT_TRUE(sampled) << sampled.error().message;
    EXPECT_EQ(sampled->pixels, 3u * 256u) << "more samples than pixels take every pixel once";
    for (std::size_t k = 0; k < names.size(); ++k) {
        double sum = 0;
        for (const AccuracyPair& pair : pairs) {
            auto exits = ideal_exits(pair.current, pair.history, Neighborhood::n9);
            ASSERT_TRUE(exits) << exits.error().message;
            const Image clipped = reference_rectify(*resolve_axis_set(names[k]), Mode::clip, Neighborhood::n9,
                                                    pair.current, pair.history, 1.0);
            for (double d : ideal_distances(pair.current, pair.history, *exits, clipped)) sum += d;
        }
        EXPECT_NEAR(sampled->mean[k], sum / (3 * 256), 1e-6) << names[k];
    }
    // dop32 holds the R, G, B axes, so it lies inside the box: along each ray it stops no later.
    EXPECT_GT(sampled->mean[0], sampled->mean[1]);

    // A sample is fixed by its seed alone.
    auto a = sampled_ideal_distances(pairs, sets, Neighborhood::n9, 20, 7);
    auto b = sampled_ideal_distances(pairs, sets, Neighborhood::n9, 20, 7);
    auto c = sampled_ideal_distances(pairs, sets, Neighborhood::n9, 20, 8);
    ASSERT_TRUE(a && b && c);
    EXPECT_EQ(a->pixels, 60u);
    EXPECT_EQ(a->mean, b->mean);
    EXPECT_NE(a->mean, c->mean);
}

} // namespace
} // namespace kdop
