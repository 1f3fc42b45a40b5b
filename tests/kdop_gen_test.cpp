// kdop-gen registry with a project's own shaders and functions, run as kdop_add_variants() runs it:
// includes resolved, the shader embedded with its interface, the depfile listing what it read, and
// bad shaders refused with a message naming the file, a non-zero exit and nothing written.
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace kdop {
namespace {
namespace fs = std::filesystem;

constexpr const char* kShader = R"(#version 450
#include "dop22-clip-n9.glsl"
#include "blend.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D current_frame;
layout(set = 1, binding = 3, rgba32f) uniform writeonly image2D resolved;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    vec3 n[9];
    for (int i = 0; i < 9; ++i)
        n[i] = texelFetch(current_frame, p + ivec2(i % 3 - 1, i / 3 - 1), 0).rgb;
    imageStore(resolved, p, vec4(blend(kdop_dop22_clip_n9(n[4], vec3(0), n), n[4]), 1));
}
)";

struct Generation {
    test::TempDir dir;
    fs::path header() const { return dir / "out" / "shaders.h"; }
    fs::path source() const { return dir / "out" / "shaders.cpp"; }
    test::CommandResult run(const std::string& shaders, const std::string& more = "") const {
        return test::run(test::kdop_gen_binary() + " registry --sets dop22 --modes clip --neighborhoods n9 --header " +
                         header().string() + " --source " + source().string() + " --namespace app --shaders " +
                         shaders + " " + more);
    }
};

TEST(KdopGen, EmbedsAProjectShaderWithTheFunctionsItIncludes) {
    Generation g;
    fs::create_directories(g.dir / "src");
    test::write_file(g.dir / "src" / "resolve.comp", kShader);
    test::write_file(g.dir / "src" / "blend.glsl", "vec3 blend(vec3 a, vec3 b) { return mix(a, b, 0.1); }\n");
    const fs::path depfile = g.dir / "out" / "shaders.d", functions = g.dir / "out" / "functions";
    auto r = g.run((g.dir / "src" / "resolve.comp").string(),
                   "--depfile " + depfile.string() + " --functions " + functions.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;

    const std::string source = test::read_file(g.source());
    EXPECT_NE(source.find(R"({"resolve", "", kdop::Mode::shader)"), std::string::npos) << source;
    EXPECT_NE(source.find(R"({1, 3, kdop::DescriptorType::storage_image, "resolved", 1, 0x20, 0, 109})"),
              std::string::npos)
        << "the shader's own interface, reflected";
    EXPECT_NE(source.find(R"({"dop22-clip-n9", "dop22", kdop::Mode::clip)"), std::string::npos);

    const std::string rule = test::read_file(depfile);
    EXPECT_EQ(rule.rfind(g.header().string() + ":", 0), 0u) << rule;
    EXPECT_NE(rule.find((g.dir / "src" / "resolve.comp").string()), std::string::npos) << rule;
    EXPECT_NE(rule.find((g.dir / "src" / "blend.glsl").string()), std::string::npos) << rule;

    EXPECT_EQ(test::read_file(functions / "dop22-clip-n9.glsl"),
              test::run(test::kdop_binary() + " show dop22-clip-n9").out);
    EXPECT_EQ(test::read_file(functions / "dop22-clip-n9.hlsl"),
              test::run(test::kdop_binary() + " show --hlsl dop22-clip-n9").out);
    EXPECT_EQ(test::read_file(functions / "dop22-clip-n9.wgsl"),
              test::run(test::kdop_binary() + " show --wgsl dop22-clip-n9").out);
}

// A loop-form function enables the extension its [[unroll]] needs itself, so it compiles wherever it
// is included, after the shader's own code (a fragment shader here, as a resolve pass would be).
TEST(KdopGen, ALoopFormFunctionCompilesInsideAProjectShader) {
    Generation g;
    test::write_file(g.dir / "resolve_pass.frag", R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D frames[2];
layout(location = 0) out vec4 resolved;
#include "dop22-varclip-n9-loop.glsl"
void main()
{
    vec3 n[9];
    for (int i = 0; i < 9; ++i)
        n[i] = texelFetch(frames[0], ivec2(gl_FragCoord.xy) + ivec2(i % 3 - 1, i / 3 - 1), 0).rgb;
    resolved = vec4(kdop_dop22_varclip_n9_loop(n[4], texelFetch(frames[1], ivec2(gl_FragCoord.xy), 0).rgb, 1.0, n), 1);
}
)");
    auto r =
        test::run(test::kdop_gen_binary() + " registry --sets dop22 --modes varclip --neighborhoods n9 --forms loop" +
                  " --header " + g.header().string() + " --source " + g.source().string() +
                  " --namespace app --shaders " + (g.dir / "resolve_pass.frag").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string source = test::read_file(g.source());
    EXPECT_NE(source.find(R"({"resolve_pass", "", kdop::Mode::shader)"), std::string::npos) << source;
    EXPECT_NE(source.find("kdop::ShaderStage::fragment"), std::string::npos);
}

// An HLSL shader, the stage from its suffix, the entry point given, the HLSL function included;
// registers become bindings as glslang maps them, the spaces sets.
TEST(KdopGen, EmbedsAnHlslShaderWithItsRegistersAsBindings) {
    Generation g;
    test::write_file(g.dir / "taa.cs.hlsl", R"(#include "dop22-clip-n9.hlsl"
Texture2D<float4> current_frame : register(t1);
SamplerState point_sampler : register(s2);
RWTexture2D<float4> resolved : register(u0, space1);
cbuffer Parameters : register(b3) { float2 motion; float weight; };
[numthreads(8, 4, 1)]
void CSMain(uint3 id : SV_DispatchThreadID)
{
    float3 n[9];
    for (int i = 0; i < 9; ++i)
        n[i] = current_frame.SampleLevel(point_sampler, (float2(id.xy) + motion) / 64.0, 0).rgb;
    resolved[id.xy] = float4(lerp(kdop_dop22_clip_n9(n[4], float3(0, 0, 0), n), n[4], weight), 1);
}
)");
    auto r = g.run((g.dir / "taa.cs.hlsl").string(), "--hlsl-entry CSMain");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string source = test::read_file(g.source());
    EXPECT_NE(source.find(R"({"taa", "", kdop::Mode::shader)"), std::string::npos) << source;
    EXPECT_NE(source.find(R"("CSMain", {8, 4, 1})"), std::string::npos) << source;
    for (const char* binding : {R"({0, 1, kdop::DescriptorType::sampled_image, "current_frame", 1, 0x20, 0, 0})",
                                R"({0, 2, kdop::DescriptorType::sampler, "point_sampler", 1, 0x20, 0, 0})",
                                R"({0, 3, kdop::DescriptorType::uniform_buffer, "Parameters", 1, 0x20, 12, 0})",
                                R"({1, 0, kdop::DescriptorType::storage_image, "resolved", 1, 0x20, 0, 109})"})
        EXPECT_NE(source.find(binding), std::string::npos) << binding << "\n" << source;

    // The same shader with the default entry point, main, which it does not have.
    Generation without_entry;
    test::write_file(without_entry.dir / "taa.cs.hlsl", test::read_file(g.dir / "taa.cs.hlsl"));
    auto missing = without_entry.run((without_entry.dir / "taa.cs.hlsl").string());
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_NE(missing.err.find("main"), std::string::npos) << missing.err;
    EXPECT_EQ(g.run((g.dir / "taa.cs.hlsl").string(), "--hlsl-entry 'CS Main'").exit_code, 2);
}

TEST(KdopGen, RefusesABadShaderNamingItAndWritesNothing) {
    struct Case {
        const char* file;
        std::string text;
        const char* expected; // in the message
    };
    const Case cases[] = {
        {"unknown.comp", "#version 450\n#include \"dop99-clip-n9.glsl\"\nvoid main() {}\n", "dop99-clip-n9.glsl"},
        {"typo.comp", "#version 450\nlayout(local_size_x = 1) in;\nvoid main() { vec3 x = y; }\n",
         "typo.comp:3: error"},
        {"dop22-clip-n9.comp", "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n",
         "would hide the variant"},
        // What no engine resolve binds, and stages kdop makes no pipelines of.
        {"rays.comp",
         "#version 460\n#extension GL_EXT_ray_query : require\nlayout(local_size_x = 1) in;\n"
         "layout(set = 0, binding = 0) uniform accelerationStructureEXT scene;\n"
         "layout(set = 0, binding = 1) buffer Hits { float hit; } hits;\n"
         "void main() { rayQueryEXT q; rayQueryInitializeEXT(q, scene, 0, 0xff, vec3(0), 0.0, vec3(0, 0, 1), 1.0);\n"
         "    hits.hit = rayQueryProceedEXT(q) ? 1.0 : 0.0; }\n",
         "resource 'scene' is an acceleration structure"},
        {"extrude.geom", "#version 450\nlayout(points) in;\nlayout(points, max_vertices = 1) out;\nvoid main() {}\n",
         "is a geometry shader"},
        {"lookup.comp",
         "#version 450\n#extension GL_EXT_nonuniform_qualifier : require\nlayout(local_size_x = 1) in;\n"
         "layout(set = 0, binding = 0) uniform sampler2D textures[];\n"
         "layout(set = 0, binding = 1) buffer Out { vec4 color; } result;\n"
         "void main() { result.color = texelFetch(textures[nonuniformEXT(int(result.color.x))], ivec2(0), 0); }\n",
         "resource 'textures' is a runtime-sized descriptor array"},
        {"twice.frag",
         "#version 450\nlayout(set = 0, binding = 0) uniform sampler2D a;\nlayout(set = 0, binding = 0) uniform "
         "sampler2D b;\nlayout(location = 0) out vec4 color;\nvoid main() { color = texture(a, vec2(0)) + "
         "texture(b, vec2(0)); }\n",
         "share set 0 binding 0"},
        // HLSL: a mistake named by file and line, a stage from its suffix, the register collision
        // every port meets first.
        {"typo.ps.hlsl", "float4 main() : SV_Target0\n{\n    return float4(y, 0, 0, 1);\n}\n", "typo.ps.hlsl:3: error"},
        {"unknown.cs.hlsl", "#include \"dop99-clip-n9.hlsl\"\n[numthreads(1, 1, 1)] void main() {}\n",
         "dop99-clip-n9.hlsl"},
        {"hull.hs.hlsl", "float4 main() : SV_Position { return 0; }\n", "is a hull shader"},
        {"nostage.hlsl", "float4 main() : SV_Position { return 0; }\n", ".cs.hlsl, .vs.hlsl or .ps.hlsl"},
        {"collide.ps.hlsl",
         "Texture2D t : register(t0);\nSamplerState s : register(s0);\n"
         "float4 main(float4 p : SV_Position) : SV_Target0 { return t.Sample(s, p.xy); }\n",
         "t0 and s0 collide"},
        {"packed.cs.hlsl",
         "cbuffer Parameters : register(b0) { float weight; float2 motion; };\n"
         "RWTexture2D<float4> o : register(u1);\n"
         "[numthreads(1, 1, 1)] void main() { o[uint2(0, 0)] = float4(motion, weight, 1); }\n",
         "TARGET_ENV vulkan1.1"},
    };
    for (const Case& c : cases) {
        Generation g;
        test::write_file(g.dir / c.file, c.text);
        auto r = g.run((g.dir / c.file).string());
        EXPECT_EQ(r.exit_code, 1) << c.file << ": " << r.err;
        EXPECT_NE(r.err.find(c.file), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(g.dir / "out")) << c.file << ": nothing may be written";
    }
    Generation g;
    auto missing = g.run((g.dir / "absent.comp").string());
    EXPECT_EQ(missing.exit_code, 2) << "a shader that does not exist is a usage error";
    EXPECT_NE(missing.err.find("absent.comp"), std::string::npos) << missing.err;
}

} // namespace
} // namespace kdop
