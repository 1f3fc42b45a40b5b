// The registry as JSON (generator/reflection_json.h): kdop_add_variants' <header stem>.json holds
// exactly what the C++ registry it was generated with holds, entry by entry (this binary's test
// registry: a variant and GLSL and HLSL project shaders); kdop-gen writes it alone, with the .spv
// files it names, and refuses what it cannot write; kdop gen writes variants.json beside its .spv
// files; the resolve a manifest records reaches the header as constants and the JSON as "resolve".
// The schema check is the test reflection_json_schema (tests/validate_reflection.py).
#include "kdop_resolve_test_variants.h"
#include "kdop_test_shaders.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <filesystem>
#include <string>

namespace kdop {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::json;

Json read_json(const fs::path& file) { return Json::parse(test::read_file(file)); }

std::string type_name(DescriptorType type) {
    std::string name = to_string(type);
    for (char& c : name)
        if (c == ' ') c = '_';
    return name;
}

// Everything `entry` says, compared with the registry entry `v`.
void expect_equal(const Json& entry, const Variant& v) {
    SCOPED_TRACE(v.name);
    EXPECT_EQ(entry["name"], v.name);
    EXPECT_EQ(entry["kind"], v.mode == Mode::shader ? "shader" : "variant");
    EXPECT_EQ(entry["stage"], to_string(v.stage));
    EXPECT_EQ(entry["entry_point"], v.entry_point);
    EXPECT_EQ(entry["local_size"], Json::array({v.local_size[0], v.local_size[1], v.local_size[2]}));
    ASSERT_EQ(entry["bindings"].size(), v.binding_count);
    for (std::uint32_t i = 0; i < v.binding_count; ++i) {
        const Json& b = entry["bindings"][i];
        const DescriptorBinding& expected = v.bindings[i];
        EXPECT_EQ(b["set"], expected.set);
        EXPECT_EQ(b["binding"], expected.binding);
        EXPECT_EQ(b["name"], expected.name);
        EXPECT_EQ(b["type"], type_name(expected.type));
        EXPECT_EQ(b["count"], expected.count);
        EXPECT_EQ(b["stages"], expected.stages);
        EXPECT_EQ(b["block_size"], expected.block_size);
        EXPECT_EQ(b["format"], expected.format);
    }
    const Json& push = entry["push_constants"];
    EXPECT_EQ(push["size"], v.push_constant_size);
    EXPECT_EQ(push["stages"], v.push_constant_size ? vulkan_stage_bit(v.stage) : 0u);
    ASSERT_EQ(push["members"].size(), v.push_constant_count);
    for (std::uint32_t i = 0; i < v.push_constant_count; ++i) {
        EXPECT_EQ(push["members"][i]["name"], v.push_constants[i].name);
        EXPECT_EQ(push["members"][i]["offset"], v.push_constants[i].offset);
        EXPECT_EQ(push["members"][i]["size"], v.push_constants[i].size);
    }
    EXPECT_EQ(entry["color_outputs"], v.color_output_count);
    EXPECT_EQ(entry["spirv"]["words"], v.spirv_word_count);
    EXPECT_EQ(entry["spirv"]["bytes"], v.spirv_word_count * 4);
    EXPECT_EQ(entry["spirv"]["fnv1a64"], fmt::format("{:016x}", v.spirv_hash));
    if (v.mode == Mode::shader) {
        EXPECT_TRUE(entry["clip"].is_null());
    } else {
        const Json& clip = entry["clip"];
        EXPECT_EQ(clip["mode"], to_string(v.mode));
        EXPECT_EQ(clip["neighborhood"], to_string(v.neighborhood));
        EXPECT_EQ(clip["form"], to_string(v.form));
        EXPECT_EQ(clip["numerics"], to_string(v.numerics));
        EXPECT_EQ(clip["axis_count"], v.axis_count);
        EXPECT_EQ(clip["axis_set"]["name"], v.axis_set);
        EXPECT_EQ(clip["axis_set"]["axes"].size(), v.axis_count);
    }
}

TEST(ReflectionJson, EqualsTheCppRegistryItWasGeneratedWith) {
    const Json document = read_json(KDOP_TEST_SHADERS_JSON);
    EXPECT_EQ(document["format"], "kdop-reflection");
    EXPECT_EQ(document["version"], 1);
    const VariantList registry = test_shaders::variants();
    ASSERT_EQ(document["entries"].size(), registry.count);
    for (std::size_t i = 0; i < registry.count; ++i) expect_equal(document["entries"][i], registry.first[i]);
    // What only the JSON says: where the set's numbers come from, and no .spv beside a C++ registry.
    const Json& dop22 = document["entries"][0];
    EXPECT_EQ(dop22["clip"]["axis_set"]["file"], "dop22.axes");
    EXPECT_NE(dop22["clip"]["axis_set"]["provenance"].get<std::string>().find("Ikkala"), std::string::npos);
    EXPECT_TRUE(dop22["spirv"]["file"].is_null());
}

TEST(ReflectionJson, KdopGenWritesItAloneWithTheSpirvItNames) {
    test::TempDir dir;
    const fs::path json = dir / "out" / "resolve.json", spirv = dir / "out" / "spirv";
    const std::string select = " registry --sets dop22 --modes clip --neighborhoods n9 --baselines";
    auto r =
        test::run(test::kdop_gen_binary() + select + " --json " + json.string() + " --spirv-dir " + spirv.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Json document = read_json(json);
    ASSERT_GE(document["entries"].size(), 2u);
    bool baseline = false;
    for (const Json& entry : document["entries"]) {
        const std::string file = entry["spirv"]["file"];
        EXPECT_EQ(file, "spirv/" + entry["name"].get<std::string>() + ".spv") << "relative to the JSON's folder";
        EXPECT_EQ(fs::file_size(json.parent_path() / file), entry["spirv"]["bytes"].get<std::uint64_t>());
        baseline = baseline || entry["clip"]["axis_set"].is_null();
    }
    EXPECT_TRUE(baseline) << "the gather and copy baselines have no axis set";
    EXPECT_FALSE(fs::exists(dir / "out" / "resolve.h"));

    // The same run twice gives the same bytes.
    const std::string first = test::read_file(json);
    ASSERT_EQ(
        test::run(test::kdop_gen_binary() + select + " --json " + json.string() + " --spirv-dir " + spirv.string())
            .exit_code,
        0);
    EXPECT_EQ(test::read_file(json), first);

    // What it cannot write is a usage error, before anything is built.
    const fs::path nothing = dir / "nothing";
    for (const std::string& wrong : {std::string(""), " --spirv-dir " + nothing.string(),
                                     " --json " + nothing.string() + ".json --header " + nothing.string() + ".h",
                                     " --json " + dir.path().string()}) {
        auto refused = test::run(test::kdop_gen_binary() + select + wrong);
        EXPECT_EQ(refused.exit_code, 2) << wrong << ": " << refused.err;
        EXPECT_FALSE(fs::exists(nothing)) << wrong;
        EXPECT_FALSE(fs::exists(nothing.string() + ".json")) << wrong;
    }
}

TEST(ReflectionJson, KdopGenWritesVariantsJsonBesideTheSpirv) {
    test::TempDir dir;
    auto r = test::run(test::kdop_binary() + " gen --sets dop22 --modes varclip --neighborhoods n5 --out " +
                       (dir / "variants").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Json document = read_json(dir / "variants" / "variants.json");
    ASSERT_EQ(document["entries"].size(), 1u);
    const Json& entry = document["entries"][0];
    EXPECT_EQ(entry["name"], "dop22-varclip-n5");
    EXPECT_EQ(entry["spirv"]["file"], "dop22-varclip-n5.spv");
    EXPECT_EQ(fs::file_size(dir / "variants" / "dop22-varclip-n5.spv"), entry["spirv"]["bytes"].get<std::uint64_t>());
    ASSERT_EQ(entry["push_constants"]["members"].size(), 1u) << "varclip's gamma";
    EXPECT_EQ(entry["push_constants"]["members"][0]["name"], "gamma");
}

// The resolve tests/data/resolve.manifest records, as kdop choose writes one, reaches the build
// through kdop_add_variants(MANIFEST): the header declares it as constants an engine reads at compile
// time, the JSON holds it, and a registry without a manifest holds none (null in its JSON). Before
// the manifest had resolve lines, `gamma: 1.5` was "not a variant name" and nothing carried them.
TEST(ReflectionJson, CarriesTheResolveTheManifestRecords) {
    constexpr ResolveSettings r = resolve_test_variants::resolve_settings;
    static_assert(r.gamma == 1.5f && r.current_weight == 0.125f, "read at compile time");
    EXPECT_EQ(r.color_map, ColorMapKind::power);
    EXPECT_EQ(r.color_map_exponent, 2.2);
    EXPECT_EQ(r.history_filter, HistoryFilter::catmull_rom);
    EXPECT_TRUE(r.dilate_motion);
    static_assert(r.upscaling && r.upscale_filter == UpscaleFilter::gaussian && r.box_scale == BoxScale::fsr2,
                  "how the resolve upscaled, read at compile time");
    static_assert(r.sample_distance.kind == SampleDistance::Kind::ue4 && r.sample_distance.at(2) == 1.3f);
    ASSERT_NE(resolve_test_variants::variants().find("aabb-varclip-n9"), nullptr);

    const Json document = read_json(KDOP_RESOLVE_TEST_JSON);
    EXPECT_EQ(document["resolve"], Json::parse(R"({"gamma": 1.5, "current_weight": 0.125, "color_map": "gamma:2.2",
                                                   "history_filter": "catmull-rom", "dilate_motion": true,
                                                   "upscale": {"filter": "gaussian", "sample_distance": "ue4",
                                                               "box_scale": "fsr2"}})"));
    EXPECT_TRUE(read_json(KDOP_TEST_SHADERS_JSON)["resolve"].is_null()) << "no manifest, no resolve";

    // kdop gen --manifest writes it into variants.json too; kdop-gen's header declares nothing
    // without a manifest, so code that needs the settings fails to build rather than guess gamma = 1.
    test::TempDir dir;
    const std::string manifest = (fs::path(KDOP_TEST_DATA_DIR) / "resolve.manifest").string();
    auto gen = test::run(test::kdop_binary() + " gen --manifest " + manifest + " --out " + (dir / "gen").string());
    ASSERT_EQ(gen.exit_code, 0) << gen.err;
    EXPECT_EQ(read_json(dir / "gen" / "variants.json")["resolve"], document["resolve"]);
    auto plain =
        test::run(test::kdop_gen_binary() + " registry --sets aabb --modes varclip --neighborhoods n9 --header " +
                  (dir / "plain.h").string() + " --source " + (dir / "plain.cpp").string() + " --namespace plain");
    ASSERT_EQ(plain.exit_code, 0) << plain.err;
    EXPECT_EQ(test::read_file(dir / "plain.h").find("resolve_settings"), std::string::npos);
}

} // namespace
} // namespace kdop
