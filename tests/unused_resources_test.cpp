// Resources a shader declares and its entry point does not use (generator/unused_resources.h): not
// in the SPIR-V, so not in the reflection, and kdop-gen says so, naming the file and the resource,
// and lists them in the JSON, which stays valid against docs/reflection.schema.json. The case the
// finding came from: an HLSL port that reads with Load, which needs no sampler, where its GLSL
// original's texelFetch took one.
#include "tests/test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace kdop {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr const char* kGlslResolve = R"(#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform texture2D current_texture;
layout(set = 0, binding = 1) uniform sampler nearest_sampler;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D resolved_frame;
void main()
{
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    imageStore(resolved_frame, p, texelFetch(sampler2D(current_texture, nearest_sampler), p, 0));
}
)";

// Its HLSL port: Load reads a texel without a sampler, so nearest_sampler is left unused.
constexpr const char* kHlslResolve = R"(Texture2D<float4> current_texture : register(t0);
SamplerState nearest_sampler : register(s1);
RWTexture2D<float4> resolved_frame : register(u2);
[numthreads(8, 8, 1)]
void main(uint3 id : SV_DispatchThreadID)
{
    resolved_frame[id.xy] = current_texture.Load(int3(id.xy, 0));
}
)";

struct Registry {
    test::CommandResult result;
    Json json;
};

// kdop-gen registry of dop22-clip-n9, its reflection into `json`, the shaders to follow.
std::vector<std::string> registry_command(const fs::path& json) {
    return {test::kdop_gen_binary(), "registry", "--sets", "dop22",       "--modes",  "clip",
            "--neighborhoods",       "n9",       "--json", json.string(), "--shaders"};
}

// kdop-gen registry --json over `shaders`, each written into `dir` as name -> text.
Registry generate(const test::TempDir& dir, const std::vector<std::pair<std::string, std::string>>& shaders) {
    std::vector<std::string> command = registry_command(dir / "registry.json");
    for (const auto& [name, text] : shaders) {
        test::write_file(dir / name, text);
        command.push_back((dir / name).string());
    }
    Registry out{test::run(command), Json()};
    if (out.result.exit_code == 0) out.json = Json::parse(test::read_file(dir / "registry.json"));
    return out;
}

const Json& entry(const Json& document, const std::string& name) {
    for (const Json& e : document["entries"])
        if (e["name"] == name) return e;
    static const Json none;
    ADD_FAILURE() << "no entry " << name;
    return none;
}

std::vector<std::string> binding_names(const Json& e) {
    std::vector<std::string> names;
    for (const Json& b : e["bindings"]) names.push_back(b["name"]);
    return names;
}

TEST(UnusedResources, AnHlslPortsUnusedSamplerIsNamedInAWarningAndTheJson) {
    test::TempDir dir;
    const Registry r = generate(dir, {{"resolve.comp", kGlslResolve}, {"hlsl_resolve.cs.hlsl", kHlslResolve}});
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err << "\na warning, not an error";

    // The two tables differ by the sampler, as the SPIR-V does.
    EXPECT_EQ(binding_names(entry(r.json, "resolve")),
              (std::vector<std::string>{"current_texture", "nearest_sampler", "resolved_frame"}));
    EXPECT_EQ(binding_names(entry(r.json, "hlsl_resolve")),
              (std::vector<std::string>{"current_texture", "resolved_frame"}));

    // ... and it is said: the file, the resource, where it was declared and why it is missing.
    const std::string hlsl_file = (dir / "hlsl_resolve.cs.hlsl").string();
    EXPECT_NE(r.result.err.find(hlsl_file + ": warning: sampler 'nearest_sampler' (set 0, binding 1) is not used by "
                                            "the entry point 'main', so it is not in the SPIR-V and the reflection "
                                            "has no binding for it\n"),
              std::string::npos)
        << r.result.err;
    EXPECT_EQ(r.result.err.find("resolve.comp"), std::string::npos) << "the GLSL resolve uses its sampler\n"
                                                                    << r.result.err;
    EXPECT_EQ(entry(r.json, "hlsl_resolve")["unused_resources"],
              Json::parse(R"([{"name": "nearest_sampler", "type": "sampler"}])"));
    EXPECT_EQ(entry(r.json, "resolve")["unused_resources"], Json::array());
    EXPECT_EQ(entry(r.json, "dop22-clip-n9")["unused_resources"], Json::array()) << "a variant";

    // The JSON with an unused resource in it is what the schema describes.
    auto valid = test::run({KDOP_PYTHON, fs::path(KDOP_SOURCE_DIR) / "tests" / "validate_reflection.py",
                            fs::path(KDOP_SOURCE_DIR) / "docs" / "reflection.schema.json", dir / "registry.json"});
    EXPECT_EQ(valid.exit_code, 0) << valid.out << valid.err;
}

// GLSL's unused resources are dropped too (by SPIRV-Tools' optimizer, where HLSL's never reach the
// SPIR-V), and each kind is named as a binding would be: a block without an instance name by its
// block name; the push-constant block by its instance.
TEST(UnusedResources, EveryKindInEitherLanguageIsNamedInTheOrderDeclared) {
    test::TempDir dir;
    const Registry r = generate(dir, {{"glsl_unused.frag", R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D used_frame;
layout(set = 0, binding = 1) uniform sampler2D history_frames[2];
layout(set = 1, binding = 0) uniform Exposure { float exposure; };
layout(set = 1, binding = 1) buffer Distances { float d[]; } distances;
layout(set = 1, binding = 2, r32f) uniform imageBuffer texels;
layout(push_constant) uniform Blend { float current_weight; } blend;
layout(location = 0) out vec4 resolved;
void unused() { resolved = texture(history_frames[1], vec2(0)) * exposure; }
void main() { resolved = texelFetch(used_frame, ivec2(gl_FragCoord.xy), 0); }
)"},
                                      {"hlsl_unused.ps.hlsl", R"(Texture2D<float4> used_frame : register(t0);
cbuffer Exposure : register(b1) { float exposure; };
struct Blend { float current_weight; };
[[vk::push_constant]] ConstantBuffer<Blend> blend;
RWStructuredBuffer<float> distances : register(u2, space1);
float4 main(float4 position : SV_Position) : SV_Target0 { return used_frame.Load(int3(position.xy, 0)); }
)"}});
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    const auto unused = [&](const std::string& name) {
        std::vector<std::string> out;
        for (const Json& u : entry(r.json, name)["unused_resources"])
            out.push_back(u["type"].get<std::string>() + " " + u["name"].get<std::string>());
        return out;
    };
    EXPECT_EQ(unused("glsl_unused"), (std::vector<std::string>{"combined_image_sampler history_frames",
                                                               "uniform_buffer Exposure", "storage_buffer distances",
                                                               "storage_texel_buffer texels", "push_constants blend"}));
    EXPECT_EQ(unused("hlsl_unused"), (std::vector<std::string>{"uniform_buffer Exposure", "push_constants blend",
                                                               "storage_buffer distances"}));
    for (const std::string& line :
         {(dir / "glsl_unused.frag").string() + ": warning: combined image sampler 'history_frames' (set 0, binding 1)",
          (dir / "glsl_unused.frag").string() +
              ": warning: push-constant block 'blend' is not used by the entry point "
              "'main', so it is not in the SPIR-V and the reflection has no push constants",
          (dir / "hlsl_unused.ps.hlsl").string() + ": warning: uniform buffer 'Exposure' (set 0, binding 1)",
          (dir / "hlsl_unused.ps.hlsl").string() + ": warning: storage buffer 'distances' (set 1, binding 2)"})
        EXPECT_NE(r.result.err.find(line), std::string::npos) << line << "\n" << r.result.err;
}

// An unused resource's type is the one its binding has when it is used: the syntax tree's types
// (declared_resources.cpp) and the SPIR-V's (shader_reflection.cpp) are read apart and must agree,
// and both are docs/embedding.md's table (a samplerBuffer is a uniform texel buffer in both).
TEST(UnusedResources, AResourceHasOneTypeUsedOrNot) {
    const std::string glsl_resources = R"(#version 450
layout(local_size_x = 1) in;
layout(set = 0, binding = 0) uniform sampler2D frame;
layout(set = 0, binding = 1) uniform texture2D texels;
layout(set = 0, binding = 2) uniform sampler nearest;
layout(set = 0, binding = 3, rgba32f) uniform image2D target;
layout(set = 0, binding = 4) uniform samplerBuffer lookup;
layout(set = 0, binding = 5, r32f) uniform imageBuffer written;
layout(set = 0, binding = 6) uniform Parameters { float weight; } parameters;
layout(set = 0, binding = 7) buffer Distances { float d[]; } distances;
)";
    const std::string hlsl_resources = R"(Texture2D<float4> texels : register(t1);
SamplerState nearest : register(s2);
RWTexture2D<float4> target : register(u3);
Buffer<float4> lookup : register(t4);
RWBuffer<float> written : register(u5);
cbuffer Parameters : register(b6) { float weight; };
RWStructuredBuffer<float> distances : register(u7);
)";
    const std::string glsl_use = "distances.d[0] = texture(frame, vec2(0)).r + texelFetch(sampler2D(texels, nearest), "
                                 "ivec2(0), 0).r + imageLoad(target, ivec2(0)).r + texelFetch(lookup, 0).r + "
                                 "imageLoad(written, 0).r + parameters.weight;";
    const std::string hlsl_use = "distances[0] = texels.SampleLevel(nearest, float2(0, 0), 0).r + target[uint2(0, "
                                 "0)].r + lookup[0].r + written[0] + weight;";
    test::TempDir dir;
    const Registry r = generate(
        dir, {{"glsl_used.comp", glsl_resources + "void main() { " + glsl_use + " }\n"},
              {"glsl_unused.comp", glsl_resources + "void main() {}\n"},
              {"hlsl_used.cs.hlsl", hlsl_resources + "[numthreads(1, 1, 1)] void main() { " + hlsl_use + " }\n"},
              {"hlsl_unused.cs.hlsl", hlsl_resources + "[numthreads(1, 1, 1)] void main() {}\n"}});
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    const auto typed = [&](const std::string& name, const char* list) {
        std::vector<std::string> out;
        for (const Json& b : entry(r.json, name)[list])
            out.push_back(b["name"].get<std::string>() + " " + b["type"].get<std::string>());
        return out;
    };
    const std::vector<std::string> glsl{
        "frame combined_image_sampler", "texels sampled_image",        "nearest sampler",
        "target storage_image",         "lookup uniform_texel_buffer", "written storage_texel_buffer",
        "parameters uniform_buffer",    "distances storage_buffer"};
    EXPECT_EQ(typed("glsl_used", "bindings"), glsl);
    EXPECT_EQ(typed("glsl_unused", "unused_resources"), glsl);
    EXPECT_EQ(typed("glsl_used", "unused_resources"), std::vector<std::string>{});
    // HLSL has no combined image sampler; its cbuffer has no instance name.
    std::vector<std::string> hlsl(glsl.begin() + 1, glsl.end());
    hlsl[hlsl.size() - 2] = "Parameters uniform_buffer";
    EXPECT_EQ(typed("hlsl_used", "bindings"), hlsl);
    EXPECT_EQ(typed("hlsl_unused", "unused_resources"), hlsl);
    EXPECT_EQ(typed("hlsl_used", "unused_resources"), std::vector<std::string>{});
}

// Shaders that use what they declare get no warning: the examples, whose resources reach the
// entry point in every way kdop reflects (arrays, a texture and sampler joined in sampler2D(),
// cbuffers and ConstantBuffers, push constants, storage buffers and images).
TEST(UnusedResources, TheExamplesShadersUseEverythingTheyDeclare) {
    test::TempDir dir;
    const fs::path examples = fs::path(KDOP_SOURCE_DIR) / "examples";
    std::vector<std::string> command = registry_command(dir / "examples.json");
    for (const char* file :
         {"taa_resolve/taa_resolve.comp", "engine_resolve/resolve_compute.comp", "engine_resolve/fullscreen.vert",
          "engine_resolve/resolve_fragment.frag", "engine_resolve/hlsl_resolve_compute.cs.hlsl",
          "engine_resolve/hlsl_fullscreen.vs.hlsl", "engine_resolve/hlsl_resolve_fragment.ps.hlsl",
          "engine_resolve/upscale_compute.comp", "engine_resolve/hlsl_upscale_compute.cs.hlsl"})
        command.push_back((examples / file).string());
    const test::CommandResult r = test::run(command);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
}

} // namespace
} // namespace kdop
