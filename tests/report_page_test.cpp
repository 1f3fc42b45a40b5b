// report.html and its viewer's frames (temporal/viewer_frames.h, temporal/taa_report_page.h): which
// frames are kept, that their images are the measured outputs, and what the page holds. The page
// in a real browser is tests/report_page_browser.py's.
#include "flip/flip.h"
#include "flip/magma.h"
#include "images/image_io.h"
#include "images/srgb.h"
#include "temporal/viewer_frames.h"
#include "test_support.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <set>

namespace kdop {
namespace {

namespace fs = std::filesystem;

TEST(ViewerFrames, SpreadsFramesEvenlyWithBothEnds) {
    EXPECT_EQ(spread_frames(10, 29, 0), (std::vector<std::size_t>{}));
    EXPECT_EQ(spread_frames(10, 29, 1), (std::vector<std::size_t>{10}));
    EXPECT_EQ(spread_frames(10, 29, 2), (std::vector<std::size_t>{10, 29}));
    EXPECT_EQ(spread_frames(10, 29, 4), (std::vector<std::size_t>{10, 16, 23, 29})); // 10 + 19k/3, rounded
    EXPECT_EQ(spread_frames(3, 5, 8), (std::vector<std::size_t>{3, 4, 5}));          // every frame, no more
    const auto many = spread_frames(100, 199, 8);
    ASSERT_EQ(many.size(), 8u);
    EXPECT_EQ(many.front(), 100u);
    EXPECT_EQ(many.back(), 199u);
    EXPECT_TRUE(std::adjacent_find(many.begin(), many.end(), std::greater_equal<>()) == many.end());
}

// A 4x4 frame of one gray.
Image gray(float value) {
    Image image(4, 4);
    for (glm::vec4& p : image.pixels) p = glm::vec4(value, value, value, 1.0f);
    return image;
}

// Runs the writers into `dir`, as an output set does.
void write_into(const fs::path& dir, const StagedImages& images) {
    for (const OutputWriter& w : images.writers(dir)) {
        fs::create_directories(w.path.parent_path());
        ASSERT_TRUE(w.write(w.path));
    }
}

// A 4x4 FLIP map of one value.
std::vector<float> flat_map(float value) { return std::vector<float>(16, value); }

// Whether `shown` (a map as read back from its PNG) is `value` in magma, through 8-bit sRGB.
bool shows_in_magma(const Image& shown, float value) {
    const glm::vec3 expected = flip::magma_srgb(value);
    for (int c = 0; c < 3; ++c)
        if (std::abs(linear_to_srgb(shown.at(1, 1)[c]) - expected[c]) > 0.6f / 255) return false;
    return true;
}

// A measured frame as the evaluation offers it, its outputs counted in `fetched` when asked for.
MeasuredFrame offered(std::string_view sequence, std::size_t index, std::span<const FrameFigures> figures,
                      const std::vector<const Image*>& outputs, std::span<const std::vector<float>> maps,
                      const Image* truth, std::size_t* fetched = nullptr) {
    return {.sequence = sequence,
            .index = index,
            .figures = figures,
            .maps = maps,
            .outputs = [outputs, fetched]() -> Result<std::vector<const Image*>> {
                if (fetched) ++*fetched;
                return outputs;
            },
            .truth = truth};
}

// Fed frame after frame, it keeps the spread and each variant's worst frame (the earliest of
// equals), stages their outputs and maps and drops the frames that stop being worst; what it
// writes are those frames' outputs and maps, not later ones'. It asks for the outputs of the frames
// it keeps alone (on the device each is a read-back).
TEST(ViewerFrames, KeepsTheSpreadAndEachVariantsWorstFrame) {
    StagedImages images;
    ViewerFrames viewer(3, {"a", "b"}, images, {});
    viewer.plan("moving", "moving", 2, 10, {.ghosting = true, .shimmer = false}, ColorRange::ldr, false);
    viewer.measuring("moving");
    // Variant a is worst at 4 (0.5), and again at 8 (0.5, later, so 4 stays); b rises to 9.
    const std::vector<std::pair<double, double>> ghosting{{0.1, 0.1}, {0.2, 0.2}, {0.5, 0.3}, {0.1, 0.1}, {0.3, 0.4},
                                                          {0.2, 0.5}, {0.5, 0.2}, {0.4, 0.6}, {0.3, 0.1}};
    const Image truth = gray(0.5f);
    std::size_t fetched = 0;
    for (std::size_t i = 2; i <= 10; ++i) {
        const auto [a, b] = ghosting[i - 2];
        const std::vector<FrameFigures> figures{{"moving", i, {NAN, a}}, {"moving", i, {NAN, b}}};
        const Image output_a = gray(float(i) / 20), output_b = gray(float(i) / 20 + 0.25f);
        const std::vector<const Image*> outputs{&output_a, &output_b};
        const std::vector<std::vector<float>> maps{flat_map(float(i) / 10), flat_map(1.0f - float(i) / 20)};
        ASSERT_TRUE(viewer.offer(offered("moving", i, figures, outputs, maps, &truth, &fetched)));
    }
    EXPECT_EQ(fetched, 7u) << "frames 5 and 8 are neither spread nor a worst so far";
    // A frame of a sequence not planned is not kept.
    const std::vector<FrameFigures> other{{"other", 3, {NAN, 1.0}}, {"other", 3, {NAN, 1.0}}};
    const std::vector<const Image*> outputs{&truth, &truth};
    ASSERT_TRUE(viewer.offer(offered("other", 3, other, outputs, {}, &truth, &fetched)));
    EXPECT_EQ(fetched, 7u);

    EXPECT_EQ(viewer.staged_frames(), 2u) << "the spread frames are written as they are measured; 4 and 9 staged";
    auto shown = viewer.write();
    ASSERT_TRUE(shown) << shown.error().message;
    ASSERT_EQ(shown->size(), 1u);
    const ViewerSequence& s = shown->front();
    EXPECT_EQ(s.frames, (std::vector<std::size_t>{2, 4, 6, 9, 10})); // spread 2, 6, 10; worst 4 (a), 9 (b)
    EXPECT_EQ(s.worst, (std::vector<std::size_t>{4, 9}));
    ASSERT_EQ(s.figures.size(), 5u);
    EXPECT_EQ(s.figures[1], (std::vector<double>{0.5, 0.3}));
    EXPECT_EQ(s.map, "LDR-FLIP against the aliased frame");
    EXPECT_EQ(s.width, 4u);

    test::TempDir dir;
    write_into(dir.path(), images);
    for (std::size_t frame : s.frames) {
        auto a = read_image((dir / viewer_image_path(s, frame, "a")).string());
        auto b = read_image((dir / viewer_image_path(s, frame, "b")).string());
        auto map_a = read_image((dir / viewer_image_path(s, frame, "a", true)).string());
        auto map_b = read_image((dir / viewer_image_path(s, frame, "b", true)).string());
        auto aliased = read_image((dir / viewer_image_path(s, frame, "aliased")).string());
        ASSERT_TRUE(a && b && map_a && map_b && aliased) << frame;
        // Each frame's own output (through 8-bit sRGB) and map, not those of a later frame staged at
        // the same name.
        EXPECT_NEAR(a->at(1, 1).r, float(frame) / 20, 0.01f) << frame;
        EXPECT_NEAR(b->at(1, 1).r, float(frame) / 20 + 0.25f, 0.01f) << frame;
        EXPECT_TRUE(shows_in_magma(*map_a, float(frame) / 10)) << frame;
        EXPECT_TRUE(shows_in_magma(*map_b, 1.0f - float(frame) / 20)) << frame;
    }
    std::size_t written = 0;
    for (const auto& entry : fs::recursive_directory_iterator(dir.path())) written += entry.is_regular_file();
    EXPECT_EQ(written, 5u * 5u) << "per frame: the truth, two outputs and their maps";
}

// A shimmer sequence shows the maps its figures were measured with (against the output before:
// ResolveGpu.MeasuredFramesCarryTheMapsTheirFiguresAreMeansOf); after a camera cut there is none,
// and no map is written. A frame offered without its maps is refused: the viewer computes none.
TEST(ViewerFrames, ShowsTheMapsTheFiguresWereMeasuredWith) {
    StagedImages images;
    ViewerFrames viewer(2, {"a"}, images, {});
    viewer.plan("still", "scene", 1, 2, {.ghosting = false, .shimmer = true}, ColorRange::ldr, false);
    viewer.measuring("scene");
    const Image truth = gray(0.5f), now = gray(0.6f);
    const std::vector<const Image*> outputs{&now};
    const std::vector<FrameFigures> first{{"still", 1, {NAN, NAN}}}, second{{"still", 2, {0.3, NAN}}};
    const std::vector<std::vector<float>> none{{}}, measured{flat_map(0.3f)};
    ASSERT_TRUE(viewer.offer(offered("still", 1, first, outputs, none, &truth))); // a cut: nothing before
    ASSERT_TRUE(viewer.offer(offered("still", 2, second, outputs, measured, &truth)));
    auto without = viewer.offer(offered("still", 2, second, outputs, {}, &truth));
    ASSERT_FALSE(without);
    EXPECT_NE(without.error().message.find("FLIP map"), std::string::npos) << without.error().message;
    auto shown = viewer.write();
    ASSERT_TRUE(shown) << shown.error().message;
    const ViewerSequence& s = shown->front();
    EXPECT_EQ(s.map, "LDR-FLIP against the output before");
    EXPECT_EQ(s.worst, (std::vector<std::size_t>{2}));
    test::TempDir dir;
    write_into(dir.path(), images);
    EXPECT_FALSE(fs::exists(dir / viewer_image_path(s, 1, "a", true))) << "no output before a cut";
    auto map = read_image((dir / viewer_image_path(s, 2, "a", true)).string());
    ASSERT_TRUE(map);
    EXPECT_TRUE(shows_in_magma(*map, 0.3f));
}

// ---------------------------------------------------------------------------------------------
// kdop taa's report.html

struct ReportRun {
    test::TempDir dir;
    test::CommandResult kdop(const std::string& args) const { return test::run(test::kdop_binary() + " " + args); }
};

std::size_t occurrences(const std::string& text, const std::string& part) {
    std::size_t count = 0;
    for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
    return count;
}

// The JSON the page carries for its script.
nlohmann::json page_data(const std::string& html) {
    const std::string open = R"(<script type="application/json" id="kdop-data">)";
    const std::size_t at = html.find(open);
    if (at == std::string::npos) return {};
    const std::size_t start = at + open.size();
    return nlohmann::json::parse(html.substr(start, html.find("</script>", start) - start));
}

// The frames kept of each sequence are the documented choice, computed here from taa_frames.csv:
// the even spread and each variant's worst frame; their images are the measured outputs; the page
// shows every row, needs nothing from a network, and leaves out a figure no sequence measures.
TEST(CliReport, TheViewerShowsTheDocumentedFramesAndThePageEveryRow) {
    ReportRun t;
    const fs::path scenes = t.dir / "scenes", out = t.dir / "taa";
    auto s = t.kdop("scene --scenes grass --size 48x32 --frames 12 --out " + scenes.string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    auto r =
        t.kdop("taa --sequence " + (scenes / "grass-ghosting").string() + " " + (scenes / "grass-shimmer").string() +
               " --sets aabb dop22 --modes clip --warmup 3 --timing-rounds 2 --no-charts --viewer-frames 3 "
               "--write-frames --out " +
               out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<std::string> variants{"aabb-clip-n9", "dop22-clip-n9"};
    const auto frames = test::csv_rows(test::read_file(out / "taa_frames.csv"));
    const std::string html = test::read_file(out / "report.html");
    const nlohmann::json data = page_data(html);
    ASSERT_EQ(data["variants"], nlohmann::json(variants));
    ASSERT_EQ(data["viewer"].size(), 2u);
    for (const auto& [sequence, figure] : std::vector<std::pair<std::string, std::string>>{
             {"grass-ghosting", "ghosting"}, {"grass-shimmer", "shimmer"}}) {
        SCOPED_TRACE(sequence);
        const auto shown = std::find_if(data["viewer"].begin(), data["viewer"].end(),
                                        [&](const nlohmann::json& v) { return v["name"] == sequence; });
        ASSERT_NE(shown, data["viewer"].end());
        EXPECT_EQ((*shown)["figure"], figure);
        std::set<std::size_t> expected{3, 7, 11}; // spread_frames(3, 11, 3)
        std::vector<std::size_t> worst;
        for (const std::string& variant : variants) {
            double largest = -1;
            std::size_t at = 0;
            for (auto f : frames)
                if (f["sequence"] == sequence && f["variant"] == variant && !f[figure].empty() &&
                    std::stod(f[figure]) > largest)
                    largest = std::stod(f[figure]), at = std::stoul(f["frame"]);
            expected.insert(at);
            worst.push_back(at);
        }
        EXPECT_EQ((*shown)["frames"], nlohmann::json(std::vector<std::size_t>(expected.begin(), expected.end())));
        EXPECT_EQ((*shown)["worst"], nlohmann::json(worst));
        std::set<std::size_t> on_disk;
        for (const auto& entry : fs::directory_iterator(out / "viewer" / sequence / sequence))
            on_disk.insert(std::stoul(entry.path().filename().string()));
        EXPECT_EQ(on_disk, expected);
        for (std::size_t frame : expected)
            for (const std::string& variant : variants) {
                const fs::path frame_dir = out / "viewer" / sequence / sequence / fmt::format("{:04}", frame);
                auto png = read_image((frame_dir / (variant + ".png")).string());
                auto exr = read_image((out / "frames" / sequence / variant / fmt::format("{:04}.exr", frame)).string());
                ASSERT_TRUE(png && exr) << variant << " frame " << frame;
                float largest = 0;
                for (std::size_t p = 0; p < png->pixels.size(); ++p)
                    largest = std::max(largest, glm::length(glm::vec3(png->pixels[p] - exr->pixels[p])));
                EXPECT_LT(largest, 0.02f) << variant << " frame " << frame << ": the measured output, through sRGB";
                EXPECT_TRUE(fs::exists(frame_dir / "flip" / (variant + ".png"))) << variant << " frame " << frame;
                EXPECT_TRUE(fs::exists(frame_dir / "aliased.png")) << frame;
            }
    }
    // Every row in the table, the shimmer of the ghosting sequence and the ghosting of the shimmer
    // one left out: 2 shimmer columns x 2 rows and 2 ghosting columns x 2 rows (the page leaves the
    // medians to taa.csv), none shown as 0.
    for (const std::string& variant : variants) EXPECT_EQ(occurrences(html, "<td>" + variant + "</td>"), 2u) << variant;
    EXPECT_EQ(occurrences(html, "data-value=\"\">–</td>"), 8u);
    for (const char* network : {"http:", "https:", "//cdn", "@import", "url("})
        EXPECT_EQ(html.find(network), std::string::npos) << network;
    EXPECT_NE(html.find("default-src 'none'"), std::string::npos) << "the page forbids itself any fetch";

    // No viewer: no frames written and no viewer on the page.
    const fs::path none = t.dir / "none";
    auto n = t.kdop("taa --sequence " + (scenes / "grass-ghosting").string() +
                    " --sets aabb --modes clip --warmup 3 --timing-rounds 2 --no-charts --viewer-frames 0 --out " +
                    none.string());
    ASSERT_EQ(n.exit_code, 0) << n.err;
    EXPECT_FALSE(fs::exists(none / "viewer"));
    EXPECT_EQ(test::read_file(none / "report.html").find("id=\"viewer\""), std::string::npos);
}

// --picture-frame chooses the frame of each sequence's ghosting picture; one that is not measured
// is a wrong command line, and nothing is written.
TEST(CliReport, PictureFrameChoosesTheFrameOfTheGhostingPicture) {
    ReportRun t;
    const fs::path scenes = t.dir / "scenes", out = t.dir / "taa";
    auto s = t.kdop("scene --scenes grass --size 48x32 --frames 10 --out " + scenes.string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const std::string common = "taa --sequence " + (scenes / "grass-ghosting").string() +
                               " --sets aabb dop22 --modes clip --warmup 3 --timing-rounds 2 --no-charts ";
    auto r = t.kdop(common + "--picture-frame 5 --write-frames --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* variant : {"aabb-clip-n9", "dop22-clip-n9"}) {
        auto shown = read_image((out / "frames" / "grass-ghosting" / (std::string(variant) + ".exr")).string());
        auto written = read_image((out / "frames" / "grass-ghosting" / variant / "0005.exr").string());
        ASSERT_TRUE(shown && written) << variant;
        EXPECT_EQ(shown->pixels, written->pixels) << variant;
    }
    for (const char* frame : {"2", "10"}) {
        const fs::path refused = t.dir / (std::string("refused-") + frame);
        auto bad = t.kdop(common + "--picture-frame " + frame + " --out " + refused.string());
        EXPECT_EQ(bad.exit_code, 2) << bad.err;
        EXPECT_NE(bad.err.find(std::string("--picture-frame ") + frame + ": not a measured frame of --sequence"),
                  std::string::npos)
            << bad.err;
        EXPECT_FALSE(fs::exists(refused / "taa.csv"));
    }
}

} // namespace
} // namespace kdop
