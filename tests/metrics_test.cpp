// The metrics registry (temporal/metrics.h): PSNR and tPSNR as computed by hand, infinite and
// absent figures written as such, and a metric added as one registry row reaching every table
// kdop taa writes.
#include "harness/output_set.h"
#include "harness/printed_table.h"
#include "harness/variant_catalog.h"
#include "images/image_io.h"
#include "optimize/choice_report.h"
#include "optimize/optimize_tables.h"
#include "sequence/sequence.h"
#include "temporal/metrics.h"
#include "temporal/taa_report.h"
#include "temporal/taa_report_page.h"
#include "temporal/taa_run.h"
#include "temporal/taa_sources.h"
#include "tests/gpu_support.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace kdop {
namespace {
namespace fs = std::filesystem;

Image filled(std::uint32_t w, std::uint32_t h, glm::vec4 value) {
    Image image(w, h);
    for (glm::vec4& p : image.pixels) p = value;
    return image;
}

// PSNR over R, G and B with a peak of 1, as 10 log10(1 / MSE) gives it by hand.
TEST(Metrics, PsnrIsTenLogOfOneOverTheMeanSquaredError) {
    const Image reference = filled(2, 1, {0.5f, 0.5f, 0.5f, 1.0f});
    Image test = reference;
    test.at(0, 0).r += 0.25f; // one of six values off by 0.25: MSE = 0.0625 / 6
    test.at(1, 0).a = 0.0f;   // alpha is not a color
    EXPECT_NEAR(psnr(reference, test), 10.0 * std::log10(6.0 / 0.0625), 1e-9);
    EXPECT_EQ(psnr(reference, reference), INFINITY) << "identical frames";
}

// tPSNR compares the change of the output with the change of the truth: an output that moves by
// 0.125 where the truth moves by 0.25 is 0.125 off in every value, 10 log10(64) dB; one that moves
// as the truth does is infinite, however far it is from the truth. (Values a float holds exactly.)
TEST(Metrics, TemporalPsnrComparesTheOutputsChangeWithTheTruths) {
    const Image r0 = filled(3, 2, glm::vec4(0.25f)), r1 = filled(3, 2, glm::vec4(0.5f));
    const Image t0 = filled(3, 2, glm::vec4(0.25f)), t1 = filled(3, 2, glm::vec4(0.375f));
    EXPECT_NEAR(temporal_psnr(r0, r1, t0, t1), 10.0 * std::log10(64.0), 1e-9);
    const Image offset0 = filled(3, 2, glm::vec4(0.5f)), offset1 = filled(3, 2, glm::vec4(0.75f));
    EXPECT_EQ(temporal_psnr(r0, r1, offset0, offset1), INFINITY);
}

// An infinite PSNR is written as infinity in every table (inf, ∞, "inf"), and a figure not
// measured as absent (empty, –, null), never as a number.
TEST(Metrics, InfiniteAndAbsentFiguresAreWrittenAsSuch) {
    Metrics metrics = default_metrics();
    metrics[kPsnr].measured = metrics[kTpsnr].measured = true;
    TaaRow row;
    row.key = VariantKey{"aabb", Mode::clip, Neighborhood::n9};
    row.scene = "still";
    row.figures.resize(metrics.size());
    row.figures[kGhosting].mean = 0.0;
    row.figures[kPsnr].mean = INFINITY;
    const Table table = taa_table({row}, metrics);
    const auto csv = test::csv_rows(table.csv());
    EXPECT_EQ(csv.at(0).at("psnr"), "inf");
    EXPECT_EQ(csv.at(0).at("tpsnr"), "");
    const nlohmann::json json = table.json();
    EXPECT_EQ(json["rows"][0]["psnr"], "inf");
    EXPECT_TRUE(json["rows"][0]["tpsnr"].is_null());
    const std::vector<std::string> shown{"psnr", "tpsnr"};
    const std::string md = table.markdown(shown);
    EXPECT_NE(md.find("∞"), std::string::npos) << md;
    EXPECT_NE(md.find("–"), std::string::npos) << md;
}

TEST(Metrics, AnUnknownNameOrNoGhostingIsAUsageError) {
    const std::vector<std::string> unknown{"ghosting", "ssim"}, without_ghosting{"psnr"}, all{"psnr", "ghosting"};
    auto refused = metrics_named(unknown);
    ASSERT_FALSE(refused);
    EXPECT_TRUE(refused.error().usage);
    EXPECT_NE(refused.error().message.find("no metric 'ssim'; kdop measures shimmer, ghosting, psnr, tpsnr"),
              std::string::npos)
        << refused.error().message;
    auto no_ghosting = metrics_named(without_ghosting);
    ASSERT_FALSE(no_ghosting);
    EXPECT_TRUE(no_ghosting.error().usage);
    auto chosen = metrics_named(all);
    ASSERT_TRUE(chosen);
    EXPECT_TRUE((*chosen)[kPsnr].measured && (*chosen)[kGhosting].measured);
    EXPECT_FALSE((*chosen)[kShimmer].measured || (*chosen)[kTpsnr].measured);
}

// kdop choose's candidates and kdop optimize's table of axis counts take their figures' columns
// from the registry too: a test-only row measured is a column of each, a row not measured none.
TEST(Metrics, ChoosesAndOptimizesTablesTakeTheirColumnsFromTheRegistry) {
    Metrics metrics = default_metrics();
    Metric extra = metrics[kPsnr];
    extra.name = "sharpness";
    extra.measured = true;
    metrics.push_back(extra);
    const std::size_t extra_id = metrics.size() - 1;

    Candidate c;
    c.key = {"aabb", Mode::clip, Neighborhood::n9};
    c.figures.resize(metrics.size());
    c.figures[kGhosting] = {.fit = 0.02, .held_out = 0.03};
    c.figures[extra_id].held_out = 0.25;
    const Table candidates = candidates_table({c}, metrics);
    const auto rows = test::csv_rows(candidates.csv());
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_DOUBLE_EQ(std::stod(rows[0].at("validation_sharpness")), 0.25);
    EXPECT_DOUBLE_EQ(std::stod(rows[0].at("validation_ghosting")), 0.03);
    EXPECT_DOUBLE_EQ(std::stod(rows[0].at("fit_ghosting")), 0.02);
    EXPECT_FALSE(rows[0].contains("validation_psnr")) << "psnr is not measured";
    EXPECT_NE(candidates.markdown().find("held-out sharpness"), std::string::npos);

    AxisCountRow row{.axes = 4, .volume = 1, .figures = {std::vector<double>(metrics.size(), NAN)}};
    row.figures[0][kGhosting] = 0.125, row.figures[0][extra_id] = 0.5;
    const auto columns = axis_count_columns(metrics, 1, false);
    const std::string header = printed_header(columns), printed = printed_row(columns, row);
    EXPECT_NE(header.find("sharpness"), std::string::npos) << header;
    EXPECT_EQ(header.find("psnr"), std::string::npos) << header;
    EXPECT_NE(printed.find("0.500000"), std::string::npos) << printed;
    EXPECT_NE(printed.find("0.125000"), std::string::npos) << printed;
    EXPECT_NE(printed.find("–"), std::string::npos) << "no shimmer measured: " << printed;
}

// kdop taa --metrics: PSNR and tPSNR of every measured frame are what this test computes from the
// outputs kdop wrote (--write-frames) and the sequence's references; on a sequence without
// references both are absent, with a warning, and shimmer and ghosting are what they are without
// them.
TEST(CliMetrics, PsnrAndTemporalPsnrAreThoseOfTheWrittenFrames) {
    test::TempDir dir;
    auto kdop = [](const std::string& args) { return test::run(test::kdop_binary() + " " + args); };
    const fs::path scenes = dir / "scenes";
    auto made = kdop("scene --scenes grass3d --size 48x32 --frames 7 --reference-samples 2 --out " + scenes.string());
    ASSERT_EQ(made.exit_code, 0) << made.err;
    const fs::path plain = dir / "plain";
    made = kdop("scene --scenes asphalt --size 48x32 --frames 7 --out " + plain.string());
    ASSERT_EQ(made.exit_code, 0) << made.err;
    const fs::path moving = scenes / "grass3d-ghosting", without = plain / "asphalt-ghosting";
    const std::string common = " --sets aabb dop22 --modes clip --warmup 2 --timing-rounds 1 --no-charts "
                               "--viewer-frames 0 --sequence " +
                               moving.string() + " " + without.string();
    const fs::path out = dir / "out", base = dir / "base";
    auto r = kdop("taa --metrics shimmer ghosting psnr tpsnr --write-frames --out " + out.string() + common);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("psnr not measured: asphalt-ghosting has no reference frames"), std::string::npos) << r.err;
    auto b = kdop("taa --out " + base.string() + common);
    ASSERT_EQ(b.exit_code, 0) << b.err;

    auto sequence = read_sequence(moving);
    ASSERT_TRUE(sequence) << sequence.error().message;
    auto image = [](const fs::path& path) {
        auto read = read_image(path.string());
        EXPECT_TRUE(read) << path;
        return read ? std::move(*read) : Image();
    };
    std::size_t checked = 0;
    for (auto row : test::csv_rows(test::read_file(out / "taa_frames.csv"))) {
        const std::size_t f = std::stoul(row["frame"]);
        if (row["sequence"] != "grass3d-ghosting") {
            EXPECT_EQ(row["psnr"], "") << "no reference, no PSNR";
            EXPECT_EQ(row["tpsnr"], "");
            continue;
        }
        const fs::path frames = out / "frames" / "grass3d-ghosting" / row["variant"];
        const Image output = image(frames / fmt::format("{:04}.exr", f));
        const Image reference = image(sequence->frames[f].reference);
        EXPECT_NEAR(std::stod(row["psnr"]), psnr(reference, output), 1e-9) << row["variant"] << " frame " << f;
        if (f == 2) { // the first measured frame has no measured frame before it
            EXPECT_EQ(row["tpsnr"], "");
        } else {
            const double expected = temporal_psnr(image(sequence->frames[f - 1].reference), reference,
                                                  image(frames / fmt::format("{:04}.exr", f - 1)), output);
            EXPECT_NEAR(std::stod(row["tpsnr"]), expected, 1e-9) << row["variant"] << " frame " << f;
        }
        ++checked;
    }
    EXPECT_EQ(checked, 2u * 5u) << "two variants, frames 2 to 6";
    // The paper's figures are the same with the new ones beside them.
    const auto with = test::csv_rows(test::read_file(out / "taa.csv")),
               plain_rows = test::csv_rows(test::read_file(base / "taa.csv"));
    ASSERT_EQ(with.size(), plain_rows.size());
    for (std::size_t i = 0; i < with.size(); ++i)
        for (const char* column : {"shimmer", "ghosting", "ghosting_p95", "worst_ghosting_frame"})
            EXPECT_EQ(with[i].at(column), plain_rows[i].at(column)) << column;
    EXPECT_EQ(plain_rows[0].count("psnr"), 0u) << "not asked for, no column";
    auto refused = kdop("taa --metrics psnr --out " + (dir / "refused").string() + common);
    EXPECT_EQ(refused.exit_code, 2) << refused.err;
    EXPECT_FALSE(fs::exists(dir / "refused"));
}

// A metric is one registry row: one added here, measuring each output's mean red, reaches
// taa.csv, taa.json, taa_frames.csv and report.html with no other change, its figure the one the
// test computes from the written frames.
TEST(CliMetrics, ATestOnlyRegistryRowReachesEveryTable) {
    test::TempDir dir;
    const fs::path scenes = dir / "scenes";
    auto made =
        test::run(test::kdop_binary() + " scene --scenes grass --size 40x24 --frames 6 --out " + scenes.string());
    ASSERT_EQ(made.exit_code, 0) << made.err;
    Metrics metrics = default_metrics();
    metrics.push_back({.name = "mean_red",
                       .unit = "",
                       .description = "the output's mean red",
                       .compares = Compared::truth,
                       .role = MetricRole::ghosting,
                       .compute = [](const MetricFrame& f) -> Result<FlipFigure> {
                           auto output = f.flip.store().image(f.output);
                           if (!output) return std::unexpected(output.error());
                           double red = 0;
                           for (const glm::vec4& p : (*output)->pixels) red += p.r;
                           return FlipFigure{red / double((*output)->pixels.size()), {}, {}};
                       }});

    Context& context = test::gpu();
    auto sources = taa_sources(
        context, {.sequences = {(scenes / "grass-ghosting").string()}, .warmup = 2, .variants = 1, .builtin = false});
    ASSERT_TRUE(sources) << sources.error().message;
    const VariantKey key{"dop22", Mode::clip, Neighborhood::n9};
    auto spec = resolve_axis_set("dop22");
    ASSERT_TRUE(spec);
    const std::vector<VariantSpec> specs{{*spec, Mode::clip, Neighborhood::n9}};
    auto rectifiers = test::catalog().find_all(std::vector<VariantKey>{key}, "--sets");
    ASSERT_TRUE(rectifiers) << rectifiers.error().message;
    const fs::path out = dir / "out";
    auto outputs = OutputSet::prepare(out);
    ASSERT_TRUE(outputs);
    const TaaRunSettings settings{.evaluation = {.schedule = {2, 4}, .ppd = 67.0, .metrics = metrics},
                                  .width = 40,
                                  .height = 24,
                                  .timing_rounds = 1,
                                  .write_frames = true,
                                  .charts = false,
                                  .viewer_frames = 0};
    auto ran = run_taa(context, specs, *rectifiers, *sources, settings, *outputs);
    ASSERT_TRUE(ran) << ran.error().message;

    double sum = 0;
    std::size_t frames = 0;
    for (auto row : test::csv_rows(test::read_file(out / "taa_frames.csv"))) {
        auto output = read_image(
            (out / "frames" / "grass-ghosting" / key.name() / fmt::format("{:04}.exr", std::stoul(row["frame"])))
                .string());
        ASSERT_TRUE(output);
        double red = 0;
        for (const glm::vec4& p : output->pixels) red += p.r;
        EXPECT_NEAR(std::stod(row.at("mean_red")), red / double(output->pixels.size()), 1e-12);
        sum += std::stod(row.at("mean_red"));
        ++frames;
    }
    ASSERT_EQ(frames, 4u);
    const auto rows = test::csv_rows(test::read_file(out / "taa.csv"));
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_NEAR(std::stod(rows[0].at("mean_red")), sum / 4, 1e-12);
    EXPECT_FALSE(rows[0].at("mean_red_p95").empty());
    EXPECT_FALSE(rows[0].at("worst_mean_red_frame").empty());
    const auto json = nlohmann::json::parse(test::read_file(out / "taa.json"));
    EXPECT_NEAR(json["rows"][0]["mean_red"].get<double>(), sum / 4, 1e-12);
    const std::string page = test::read_file(out / "report.html");
    EXPECT_NE(page.find("mean_red (mean)"), std::string::npos);
}

} // namespace
} // namespace kdop
