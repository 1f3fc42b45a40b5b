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
