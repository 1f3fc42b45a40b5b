// A renderer's resolve declared by role (temporal/resolve_bindings.h): the map shipped for kdop's
// own upscaling resolve binds every resource and push-constant member of the shader kdop builds,
// and each way a map can be wrong is refused naming the map, the shader, the resource or member,
// the role and what it expected. No device: the reflection is the one the registry records.
#include "generator/variant_spec.h"
#include "temporal/resolve_bindings.h"
#include "temporal/taa_shader.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace kdop {
namespace {

namespace fs = std::filesystem;

const fs::path kKdopMap = fs::path(KDOP_SOURCE_DIR) / "shader_templates" / "taa_resolve.bindings.json";

// kdop's own resolve of dop22-clip-n9, upscaling: what the shipped map describes.
std::unique_ptr<RunnableVariant> kdop_upscaling_resolve() {
    ResolveOptions options;
    options.upscale = true;
    auto built = build_taa_shader(VariantSpec{*resolve_axis_set("dop22"), Mode::clip, Neighborhood::n9}, options);
    EXPECT_TRUE(built) << built.error().message;
    return built ? std::move(*built) : nullptr;
}

TEST(ResolveBindings, TheMapOfKdopsOwnResolveBindsEveryResourceAndMember) {
    auto map = read_resolve_bindings(kKdopMap);
    ASSERT_TRUE(map) << map.error().message;
    auto shader = kdop_upscaling_resolve();
    ASSERT_TRUE(shader);
    const Variant& v = shader->variant();
    auto bound = bind(*map, v);
    ASSERT_TRUE(bound) << bound.error().message;
    EXPECT_EQ(bound->resources.size(), v.binding_count);
    EXPECT_EQ(bound->values.size(), v.push_constant_count);
    ASSERT_TRUE(bound->find(ResourceRole::current));
    EXPECT_STREQ(bound->find(ResourceRole::current)->name, "color_frame");
    EXPECT_STREQ(bound->find(ResourceRole::output)->name, "rectified_history");
    EXPECT_EQ(bound->motion, MotionConvention{});
}

// kdop's motion (input pixels, y down, to the previous position) as each convention reads it.
TEST(ResolveBindings, MotionIsScaledToTheShadersConvention) {
    const MotionScale same = motion_scale({}, 160, 90);
    EXPECT_EQ(same.x, 1.0f);
    EXPECT_EQ(same.y, 1.0f);
    const MotionScale uv_up_next =
        motion_scale({MotionConvention::Units::uv, /*y_up=*/true, /*points_to_previous=*/false}, 160, 90);
    EXPECT_FLOAT_EQ(uv_up_next.x, -1.0f / 160);
    EXPECT_FLOAT_EQ(uv_up_next.y, 1.0f / 90);
}

// Each wrong map is refused, naming the map file, what is wrong and where.
TEST(ResolveBindings, EachWrongMapIsRefusedNamingWhatIsWrong) {
    auto shader = kdop_upscaling_resolve();
    ASSERT_TRUE(shader);
    const std::string head = R"({"format": "kdop-resolve-bindings", "version": 1, )";
    const std::string push = R"("push_constants": {"current_weight": "current_weight", "gamma": "gamma",
                                 "jitter": "jitter", "sample_distance": "sample_distance"})";
    const std::string resources = R"("resources": {"color_frame": "current", "history_frame": "history",
                                      "motion_frame": "motion", "rectified_history": "output"})";
    const struct {
        std::string text;
        const char* says;
    } cases[] = {
        {"{", "map.json: not JSON"},
        {R"({"format": "other", "version": 1})", "map.json: format: expected \"kdop-resolve-bindings\""},
        {head + R"("resources": {}, "extra": 1})", "map.json: the map: unknown key \"extra\""},
        {head + R"("resources": {"color_frame": "curent"}})", "resources.color_frame: \"curent\" is not a role"},
        {head + R"("resources": {"a": "current", "b": "current"}})", "the role current is also given to \"a\""},
        {head + R"("motion": {"y": "sideways"}})", "motion.y: expected \"down\" or \"up\""},
        // Against the shader's reflection:
        {head + R"("resources": {"colour": "current", "history_frame": "history", "motion_frame": "motion",
                                 "rectified_history": "output"}, )" +
             push + "}",
         "resources.colour: the shader has no resource \"colour\""},
        {head + R"("resources": {"color_frame": "output", "history_frame": "history", "motion_frame": "motion",
                                 "rectified_history": "current"}, )" +
             push + "}",
         "the role output takes a storage image"},
        {head + R"("resources": {"color_frame": "current", "history_frame": "history",
                                 "rectified_history": "output"}, )" +
             push + "}",
         "its resource \"motion_frame\" (set 0, binding 2) has no role"},
        {head + resources + R"(, "push_constants": {"current_weight": "jitter", "gamma": "gamma",
                                 "jitter": "current_weight", "sample_distance": "sample_distance"}})",
         "push_constants.current_weight: the role jitter takes 8 bytes (a vec2), and \"current_weight\" is 4"},
        {head + resources + R"(, "push_constants": {"current_weight": "current_weight", "gamma": "gamma",
                                 "jitter": "jitter"}})",
         "its push-constant member \"sample_distance\" has no role"},
        {head + resources + R"(, "push_constants": {"frame": "frame_index"}})",
         "push_constants.frame: the shader has no push-constant member \"frame\""},
    };
    for (const auto& c : cases) {
        auto map = parse_resolve_bindings(c.text, "map.json");
        auto bound = map ? bind(*map, shader->variant()) : Result<BoundResolve>(std::unexpected(map.error()));
        ASSERT_FALSE(bound) << c.text;
        EXPECT_NE(bound.error().message.find(c.says), std::string::npos) << bound.error().message;
        EXPECT_EQ(bound.error().message.find("map.json"), 0u) << bound.error().message;
    }
}

// A map without a role every resolve has: the output.
TEST(ResolveBindings, AMapWithoutTheOutputIsRefused) {
    auto shader = kdop_upscaling_resolve();
    ASSERT_TRUE(shader);
    // rectified_history given no role is refused as unbound first; with a shader of no output, the
    // missing role is what is refused.
    Variant v = shader->variant();
    std::vector<DescriptorBinding> without_output;
    for (std::uint32_t b = 0; b < v.binding_count; ++b)
        if (std::string(v.bindings[b].name) != "rectified_history") without_output.push_back(v.bindings[b]);
    v.bindings = without_output.data(), v.binding_count = std::uint32_t(without_output.size());
    auto map = parse_resolve_bindings(R"({"format": "kdop-resolve-bindings", "version": 1,
        "resources": {"color_frame": "current", "history_frame": "history", "motion_frame": "motion"},
        "push_constants": {"current_weight": "current_weight", "gamma": "gamma", "jitter": "jitter",
                           "sample_distance": "sample_distance"}})",
                                      "map.json");
    ASSERT_TRUE(map) << map.error().message;
    auto bound = bind(*map, v);
    ASSERT_FALSE(bound);
    EXPECT_NE(bound.error().message.find("no resource has the role output"), std::string::npos)
        << bound.error().message;
}

} // namespace
} // namespace kdop
