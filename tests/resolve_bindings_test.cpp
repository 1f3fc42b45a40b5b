// A renderer's resolve declared by role (temporal/resolve_bindings.h): the map shipped for kdop's
// own upscaling resolve binds every resource and push-constant member of the shader kdop builds,
// and each way a map can be wrong is refused naming the map, the shader, the resource or member,
// the role and what it expected. No device: the reflection is the one the registry records.
#include "generator/variant_spec.h"
#include "temporal/resolve_bindings.h"
#include "temporal/taa_shader.h"
#include "tests/test_support.h"

#include <fmt/format.h>
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
    EXPECT_EQ(bound->motion.units, MotionConvention::Units::pixels);
    EXPECT_EQ(bound->motion.points_to, MotionConvention::PointsTo::previous);
    EXPECT_EQ(bound->motion.y_axis, MotionConvention::YAxis::down);
}

// kdop's motion (input pixels, y down, to the previous position) as each convention reads it.
TEST(ResolveBindings, MotionIsScaledToTheShadersConvention) {
    const MotionScale same = motion_scale({}, 160, 90);
    EXPECT_EQ(same.x, 1.0f);
    EXPECT_EQ(same.y, 1.0f);
    const MotionScale uv_up_next = motion_scale(
        {MotionConvention::Units::uv, MotionConvention::PointsTo::current, MotionConvention::YAxis::up}, 160, 90);
    EXPECT_FLOAT_EQ(uv_up_next.x, -1.0f / 160);
    EXPECT_FLOAT_EQ(uv_up_next.y, 1.0f / 90);
    // Every convention: what the shader reads, read back as a sequence of that convention is read,
    // is kdop's motion again.
    const glm::vec2 motion(2.5f, -1.25f);
    for (auto units : {MotionConvention::Units::pixels, MotionConvention::Units::uv})
        for (auto points_to : {MotionConvention::PointsTo::previous, MotionConvention::PointsTo::current})
            for (auto y_axis : {MotionConvention::YAxis::down, MotionConvention::YAxis::up}) {
                const MotionConvention c{units, points_to, y_axis};
                const MotionScale s = motion_scale(c, 160, 90);
                const glm::vec2 back = canonical_motion(motion * glm::vec2(s.x, s.y), c, 160, 90);
                EXPECT_FLOAT_EQ(back.x, motion.x);
                EXPECT_FLOAT_EQ(back.y, motion.y);
            }
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
        {R"({"version": 8e8888})", "map.json: not JSON"}, // beyond a double: the fuzzer's first find
        {R"({"format": "other", "version": 1})", "map.json: format: expected \"kdop-resolve-bindings\""},
        {head + R"("resources": {}, "extra": 1})", "map.json: the map: unknown key \"extra\""},
        {head + R"("resources": {"color_frame": "curent"}})", "resources.color_frame: \"curent\" is not a role"},
        {head + R"("resources": {"a": "current", "b": "current"}})", "the role current is also given to \"a\""},
        {head + R"("motion": {"y_axis": "sideways"}})", "motion.y_axis: expected \"down\" or \"up\""},
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

// A renderer's resolve, GLSL: its own names and header, the variant through kdop_variant.glsl.
constexpr const char* kGlslResolve = R"(#version 450
#include "kdop_variant.glsl"
#include "blend.glsl"
#if KDOP_NEIGHBORS != 9
#error this resolve gathers a 3x3
#endif
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D current_color;
layout(set = 0, binding = 1) uniform sampler2D previous_output;
layout(set = 0, binding = 2) uniform sampler2D velocity;
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D resolved;
layout(push_constant) uniform Push { float blend; float width; } push;
void main()
{
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy), size = textureSize(current_color, 0);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 n[KDOP_NEIGHBORS];
    for (int i = 0; i < 9; ++i)
        n[i] = texelFetch(current_color, clamp(p + ivec2(i % 3 - 1, i / 3 - 1), ivec2(0), size - 1), 0).rgb;
    const vec2 uv = (vec2(p) + 0.5 + texelFetch(velocity, p, 0).xy) / vec2(size);
    const vec3 rectified = kdop_rectify(n[4], textureLod(previous_output, uv, 0.0).rgb, push.width, n);
    imageStore(resolved, p, vec4(blend_current(rectified, n[4], push.blend), 1.0));
}
)";

// The same in HLSL, with a separate sampler.
constexpr const char* kHlslResolve = R"(#include "kdop_variant.hlsl"
Texture2D<float4> current_color : register(t0);
Texture2D<float4> previous_output : register(t1);
SamplerState linear_clamp : register(s2);
[[vk::image_format("rgba32f")]] RWTexture2D<float4> resolved : register(u3);
struct Push
{
    float blend;
    float width;
};
[[vk::push_constant]] ConstantBuffer<Push> push;
[numthreads(8, 8, 1)]
void main(uint3 id : SV_DispatchThreadID)
{
    uint w, h;
    current_color.GetDimensions(w, h);
    if (id.x >= w || id.y >= h)
        return;
    float3 n[KDOP_NEIGHBORS];
    for (int i = 0; i < 9; ++i)
        n[i] = current_color.Load(int3(clamp(int2(id.xy) + int2(i % 3 - 1, i / 3 - 1), int2(0, 0),
                                             int2(w - 1, h - 1)), 0)).rgb;
    const float3 history = previous_output.SampleLevel(linear_clamp, (float2(id.xy) + 0.5) / float2(w, h), 0).rgb;
    resolved[id.xy] = float4(lerp(kdop_rectify(n[4], history, push.width, n), n[4], push.blend), 1);
}
)";

std::string reflected(const Variant& v) {
    std::string names;
    for (std::uint32_t b = 0; b < v.binding_count; ++b)
        names += fmt::format("{} ({}) ", v.bindings[b].name, int(v.bindings[b].type));
    for (std::uint32_t m = 0; m < v.push_constant_count; ++m)
        names += fmt::format("{}:{} ", v.push_constants[m].name, v.push_constants[m].size);
    return names;
}

// A resolve in each language builds around a variant under its own file's name, and binds with
// its map; the same shader without the include, or with an error, is refused.
TEST(ResolveBindings, ARenderersResolveBuildsAroundTheVariantAndBindsByItsMap) {
    test::TempDir dir;
    test::write_file(dir / "resolve.comp", kGlslResolve);
    test::write_file(dir / "blend.glsl", "vec3 blend_current(vec3 r, vec3 c, float w) { return r + w * (c - r); }\n");
    test::write_file(dir / "resolve.cs.hlsl", kHlslResolve);
    const VariantSpec spec{*resolve_axis_set("dop22"), Mode::varclip, Neighborhood::n9};
    const struct {
        const char* file;
        const char* map;
    } cases[] = {
        {"resolve.comp", R"({"format": "kdop-resolve-bindings", "version": 1,
            "resources": {"current_color": "current", "previous_output": "history", "velocity": "motion",
                          "resolved": "output"},
            "push_constants": {"blend": "current_weight", "width": "gamma"}})"},
        {"resolve.cs.hlsl", R"({"format": "kdop-resolve-bindings", "version": 1,
            "resources": {"current_color": "current", "previous_output": "history", "linear_clamp": "sampler",
                          "resolved": "output"},
            "push_constants": {"blend": "current_weight", "width": "gamma"}})"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.file);
        auto built = build_own_resolve(dir / c.file, spec);
        ASSERT_TRUE(built) << built.error().message;
        EXPECT_EQ(std::string((*built)->variant().name),
                  std::string(fs::path(c.file).stem().stem()) + "-dop22-varclip-n9");
        auto map = parse_resolve_bindings(c.map, "map.json");
        ASSERT_TRUE(map) << map.error().message;
        auto bound = bind(*map, (*built)->variant());
        ASSERT_TRUE(bound) << bound.error().message << "\n" << reflected((*built)->variant());
        EXPECT_STREQ(bound->find(ResourceRole::output)->name, "resolved");
    }

    // A resolve that compiles but clips with a function of its own measures no variant.
    std::string plain_text = kGlslResolve;
    plain_text.replace(plain_text.find("#include \"kdop_variant.glsl\""), 28,
                       "#define KDOP_NEIGHBORS 9\nvec3 kdop_rectify(vec3 c, vec3 h, float g, vec3 n[9]) { return h; }");
    test::write_file(dir / "plain.comp", plain_text);
    auto plain = build_own_resolve(dir / "plain.comp", spec);
    ASSERT_FALSE(plain);
    EXPECT_NE(plain.error().message.find("does not #include \"kdop_variant.glsl\""), std::string::npos)
        << plain.error().message;

    std::string broken = kGlslResolve;
    broken.replace(broken.find("push.blend"), 10, "push.blnd");
    test::write_file(dir / "broken.comp", broken);
    auto error = build_own_resolve(dir / "broken.comp", spec);
    ASSERT_FALSE(error);
    EXPECT_NE(error.error().message.find("broken.comp:23:"), std::string::npos) << error.error().message;
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
