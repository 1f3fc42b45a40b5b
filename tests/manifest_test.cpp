// A scene's variant manifest (generator/manifest.h): exactly the variants listed, in order, with
// the sets its `set:` lines name; anything else an error naming the manifest's line.
#include "generator/manifest.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace kdop {
namespace {
namespace fs = std::filesystem;

constexpr const char* kSceneSet = "name: forest\nprovenance: a test\n1 0 0\n0 1 0\n0 0 1\n0.5 0.5 1\n";

TEST(Manifest, ListsExactlyItsVariantsWithTheSetsItNames) {
    test::TempDir dir;
    fs::create_directories(dir / "axes");
    test::write_file(dir / "axes" / "forest.axes", kSceneSet);
    test::write_file(dir / "scene.manifest", "# the forest level\n"
                                             "set: axes/forest.axes   # fitted to the level\n"
                                             "\n"
                                             "forest-varclip-n5-paper\n"
                                             "  dop22-clip-n9  \n"
                                             "forest-clip-n9-loop\n"
                                             "gather-n9\n");
    auto m = read_manifest(dir / "scene.manifest");
    ASSERT_TRUE(m) << m.error().message;
    std::vector<std::string> names;
    for (const VariantSpec& s : m->variants) names.push_back(variant_name(s));
    EXPECT_EQ(names, (std::vector<std::string>{"forest-varclip-n5-paper", "dop22-clip-n9", "forest-clip-n9-loop",
                                               "gather-n9"}));
    EXPECT_EQ(m->variants[0].set.axes.size(), 4u) << "the set is the manifest's file";
    EXPECT_EQ(m->variants[1].set.axes.size(), 11u) << "dop22 is built in";
    ASSERT_EQ(m->set_files.size(), 1u);
    EXPECT_EQ(m->set_files[0], dir / "axes" / "forest.axes");
}

TEST(Manifest, AnythingElseIsAnErrorNamingItsLine) {
    struct Case {
        std::string text, expected;
    };
    const Case cases[] = {
        {"dop22-clip-n9\nforest-clip-n9\n", "scene.manifest:2: 'forest-clip-n9' is of set 'forest', which is neither"},
        {"dop22-clip-n7\n", "scene.manifest:1: 'dop22-clip-n7' is not a variant name"},
        {"dop22-clip-n9\n# again\ndop22-clip-n9\n", "scene.manifest:3: 'dop22-clip-n9' is listed twice"},
        {"set: missing.axes\n", "scene.manifest:1: cannot read the axis-set file it names: "},
        {"set: missing.axes\n", "missing.axes: does not exist"},
        {"set: bad.axes\n", "scene.manifest:1: in the set it names: "},
        {"set: forest.axes\nset: copy.axes\n", "scene.manifest:2: "},
        {"set: dop22.axes\n", "which is built in"},
        {"# nothing\n", "scene.manifest: lists no variant"},
        // The resolve's lines: each key known, once, its value in range; all five or none.
        {"gamma: 1\nblend: 0.1\ndop22-clip-n9\n", "scene.manifest:2: unknown key 'blend'"},
        {"gamma: 1\ngamma: 2\ndop22-clip-n9\n", "scene.manifest:2: 'gamma:' is given twice (first on line 1)"},
        {"gamma: 0x10\ndop22-clip-n9\n", "scene.manifest:1: gamma: '0x10' is not a number"},
        {"gamma: 101\ndop22-clip-n9\n", "scene.manifest:1: gamma: '101' is not a number above 0 and at most 100"},
        {"gamma: 1e-50\ndop22-clip-n9\n", "gamma: '1e-50' is not a number above 0"},
        {"current-weight: 0\ndop22-clip-n9\n", "scene.manifest:1: current-weight: '0' is not a number above 0"},
        {"current-weight: nan\ndop22-clip-n9\n", "current-weight: 'nan' is not a number above 0 and at most 1"},
        {"color-map: gamma:0\ndop22-clip-n9\n", "scene.manifest:1: color-map: "},
        {"history-filter: nearest\ndop22-clip-n9\n",
         "scene.manifest:1: history-filter: 'nearest' is not a history filter; use bilinear or catmull-rom"},
        {"dilate-motion: true\ndop22-clip-n9\n", "scene.manifest:1: dilate-motion: 'true' is neither yes nor no"},
        {"gamma: 1\ncolor-map: log\ndop22-clip-n9\n",
         "scene.manifest: records its resolve's settings but not current-weight, history-filter, dilate-motion"},
    };
    for (const Case& c : cases) {
        test::TempDir dir;
        test::write_file(dir / "forest.axes", kSceneSet);
        test::write_file(dir / "copy.axes", kSceneSet);
        test::write_file(dir / "bad.axes", "name: bad\nprovenance: x\n1 0\n");
        test::write_file(dir / "dop22.axes", "name: dop22\nprovenance: x\n1 0 0\n0 1 0\n0 0 1\n");
        test::write_file(dir / "scene.manifest", c.text);
        auto m = read_manifest(dir / "scene.manifest");
        ASSERT_FALSE(m) << c.text;
        EXPECT_NE(m.error().message.find(c.expected), std::string::npos) << m.error().message;
    }
    auto missing = read_manifest("/nonexistent/scene.manifest");
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.error().message.find("/nonexistent/scene.manifest: does not exist (the manifest)"),
              std::string::npos)
        << missing.error().message;
}

// The resolve a manifest records (kdop choose's): read back exactly as resolve_lines writes it,
// anywhere in the file, and none where it records none.
TEST(Manifest, RecordsTheResolveItsVariantsWereMeasuredWith) {
    test::TempDir dir;
    test::write_file(dir / "forest.axes", kSceneSet);
    test::write_file(dir / "scene.manifest", "# measured with\n"
                                             "dilate-motion: yes\n"
                                             "set: forest.axes\n"
                                             "forest-varclip-n9\n"
                                             "  color-map:   gamma:2.2   # the paper's renderer's\n"
                                             "history-filter: catmull-rom\n"
                                             "gamma: 1.25\n"
                                             "current-weight: 0.05\n");
    auto m = read_manifest(dir / "scene.manifest");
    ASSERT_TRUE(m) << m.error().message;
    ASSERT_TRUE(m->resolve);
    EXPECT_EQ(m->resolve->gamma, 1.25f);
    EXPECT_EQ(m->resolve->current_weight, 0.05f);
    EXPECT_EQ(m->resolve->color_map, ColorMapKind::power);
    EXPECT_EQ(m->resolve->color_map_exponent, 2.2);
    EXPECT_EQ(m->resolve->history_filter, HistoryFilter::catmull_rom);
    EXPECT_TRUE(m->resolve->dilate_motion);
    EXPECT_EQ(variant_name(m->variants.at(0)), "forest-varclip-n9");

    // Written back in the documented order, the fewest digits that read back the same.
    const std::string lines = resolve_lines(*m->resolve);
    EXPECT_EQ(lines, "gamma: 1.25\ncurrent-weight: 0.05\ncolor-map: gamma:2.2\nhistory-filter: catmull-rom\n"
                     "dilate-motion: yes\n");
    test::write_file(dir / "again.manifest", lines + "aabb-clip-n9\n");
    auto again = read_manifest(dir / "again.manifest");
    ASSERT_TRUE(again && again->resolve) << (again ? "no resolve" : again.error().message);
    EXPECT_EQ(resolve_lines(*again->resolve), lines);

    test::write_file(dir / "plain.manifest", "dop22-clip-n9\n");
    auto plain = read_manifest(dir / "plain.manifest");
    ASSERT_TRUE(plain) << plain.error().message;
    EXPECT_FALSE(plain->resolve);
}

// A choice judged through an upscaling resolve records how it upscaled, in three more lines, all
// three or none and only beside the five; read back, the registry's header declares them.
TEST(Manifest, RecordsHowTheResolveUpscaled) {
    test::TempDir dir;
    const std::string five = "gamma: 1\ncurrent-weight: 0.1\ncolor-map: linear\nhistory-filter: bilinear\n"
                             "dilate-motion: no\n";
    test::write_file(dir / "upscaled.manifest", five + "upscale-box-scale: fsr2\nupscale-filter: gaussian\n"
                                                       "upscale-sample-distance: 1.25\ndop22-clip-n9\n");
    auto m = read_manifest(dir / "upscaled.manifest");
    ASSERT_TRUE(m && m->resolve) << (m ? "no resolve" : m.error().message);
    EXPECT_TRUE(m->resolve->upscaling);
    EXPECT_EQ(m->resolve->upscale_filter, UpscaleFilter::gaussian);
    EXPECT_EQ(m->resolve->sample_distance.kind, SampleDistance::Kind::fixed);
    EXPECT_EQ(m->resolve->sample_distance.pixels, 1.25f);
    EXPECT_EQ(m->resolve->box_scale, BoxScale::fsr2);
    EXPECT_EQ(resolve_lines(*m->resolve),
              five + "upscale-filter: gaussian\nupscale-sample-distance: 1.25\nupscale-box-scale: fsr2\n");

    test::write_file(dir / "ue4.manifest", five + "upscale-filter: lanczos2\nupscale-sample-distance: ue4\n"
                                                  "upscale-box-scale: none\naabb-clip-n9\n");
    auto ue4 = read_manifest(dir / "ue4.manifest");
    ASSERT_TRUE(ue4 && ue4->resolve) << (ue4 ? "no resolve" : ue4.error().message);
    EXPECT_EQ(ue4->resolve->sample_distance.kind, SampleDistance::Kind::ue4);
    EXPECT_FLOAT_EQ(ue4->resolve->sample_distance.at(2), 1.3f);

    const struct {
        std::string text;
        const char* says;
    } refused[] = {
        {five + "upscale-filter: lanczos2\naabb-clip-n9\n", "but not upscale-sample-distance, upscale-box-scale"},
        {"upscale-filter: lanczos2\nupscale-sample-distance: all\nupscale-box-scale: none\naabb-clip-n9\n",
         "but not gamma"},
        {five + "upscale-filter: bicubic\nupscale-sample-distance: all\nupscale-box-scale: none\naabb-clip-n9\n",
         ":6: upscale-filter: 'bicubic' is not an upscaling filter"},
        {five + "upscale-filter: lanczos2\nupscale-sample-distance: 9\nupscale-box-scale: none\naabb-clip-n9\n",
         ":7: upscale-sample-distance: '9' is not a sample distance"},
        {five + "upscale-filter: lanczos2\nupscale-filter: lanczos2\naabb-clip-n9\n", "given twice (first on line 6)"},
    };
    for (const auto& c : refused) {
        test::write_file(dir / "refused.manifest", c.text);
        auto r = read_manifest(dir / "refused.manifest");
        ASSERT_FALSE(r) << c.text;
        EXPECT_NE(r.error().message.find(c.says), std::string::npos) << r.error().message;
    }
}

TEST(Cli, ManifestSelectsWhatListAndGenProduce) {
    test::TempDir dir;
    test::write_file(dir / "forest.axes", kSceneSet);
    test::write_file(dir / "scene.manifest", "set: forest.axes\nforest-clip-n5\ndop16-grass-varclip-n9\n");
    const std::string manifest = (dir / "scene.manifest").string();
    auto listed = test::run(test::kdop_binary() + " list --manifest " + manifest);
    EXPECT_EQ(listed.exit_code, 0) << listed.err;
    EXPECT_EQ(listed.out, "forest-clip-n5\ndop16-grass-varclip-n9\n");

    auto gen = test::run(test::kdop_binary() + " gen --manifest " + manifest + " --out " + (dir / "out").string());
    ASSERT_EQ(gen.exit_code, 0) << gen.err;
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(dir / "out")) files.push_back(entry.path().filename().string());
    std::sort(files.begin(), files.end());
    EXPECT_EQ(files, (std::vector<std::string>{"dop16-grass-varclip-n9.comp", "dop16-grass-varclip-n9.glsl",
                                               "dop16-grass-varclip-n9.hlsl", "dop16-grass-varclip-n9.spv",
                                               "dop16-grass-varclip-n9.wgsl", "forest-clip-n5.comp",
                                               "forest-clip-n5.glsl", "forest-clip-n5.hlsl", "forest-clip-n5.spv",
                                               "forest-clip-n5.wgsl", "variants.json"}));

    for (const char* conflicting : {" --sets dop22", " --modes clip", " --numerics paper", " --baselines"}) {
        auto r = test::run(test::kdop_binary() + " gen --manifest " + manifest + conflicting + " --out " +
                           (dir / "other").string());
        EXPECT_EQ(r.exit_code, 2) << conflicting;
        EXPECT_NE(r.err.find("excludes"), std::string::npos) << r.err;
    }
    EXPECT_EQ(test::run(test::kdop_binary() + " list --all --manifest " + manifest).exit_code, 2);
    EXPECT_FALSE(fs::exists(dir / "other"));
}

} // namespace
} // namespace kdop
