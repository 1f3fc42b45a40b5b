// The names the registry and the JSON give bindings, one rule in GLSL and HLSL (docs/embedding.md,
// "Binding names"): the examples of that section, each completed into a shader, reflect as its
// comments say, and alike in both languages; the engine example's HLSL ports bind every name its
// GLSL resolves bind.
#include "generator/project_shader.h"
#include "kdop_test_shaders.h"
#include "tests/test_support.h"

#include <kdop/vulkan_pipeline.h>

#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

namespace kdop {
namespace {
namespace fs = std::filesystem;

// The fenced block of `language` in the section "### Binding names" of docs/embedding.md.
std::string documented_example(const std::string& language) {
    const std::string docs = test::read_file(fs::path(KDOP_SOURCE_DIR) / "docs" / "embedding.md");
    const std::size_t section = docs.find("\n### Binding names\n");
    if (section == std::string::npos) return {};
    const std::size_t end = docs.find("\n#", section + 1);
    const std::size_t fence = docs.find("```" + language + "\n", section);
    if (fence == std::string::npos || fence > end) return {};
    const std::size_t begin = fence + language.size() + 4;
    return docs.substr(begin, docs.find("```", begin) - begin);
}

// The names each line's comment says, `// "name"`, in the order written.
std::vector<std::string> commented_names(const std::string& example) {
    static const std::regex commented(R"re(// "([^"]+)"\s*$)re");
    std::vector<std::string> names;
    std::size_t start = 0;
    while (start < example.size()) {
        const std::size_t eol = example.find('\n', start);
        const std::string line = example.substr(start, eol - start);
        std::smatch m;
        if (std::regex_search(line, m, commented)) names.push_back(m[1]);
        start = eol == std::string::npos ? example.size() : eol + 1;
    }
    return names;
}

// The bindings' names, in set and binding order, of `source` built as the project shader `file`.
std::vector<std::string> reflected_names(const std::string& file, const std::string& source) {
    test::TempDir dir;
    test::write_file(dir / file, source);
    auto shader = build_project_shader(dir / file, {});
    if (!shader) ADD_FAILURE() << shader.error().message;
    std::vector<std::string> names;
    if (shader)
        for (const BindingInfo& b : shader->built.interface.bindings) names.push_back(b.name);
    return names;
}

TEST(BindingNames, TheDocumentedExamplesReflectAsTheirCommentsSayInBothLanguages) {
    const std::string glsl = documented_example("glsl"), hlsl = documented_example("hlsl");
    ASSERT_FALSE(glsl.empty()) << "docs/embedding.md has no GLSL example under \"### Binding names\"";
    ASSERT_FALSE(hlsl.empty()) << "docs/embedding.md has no HLSL example under \"### Binding names\"";
    const std::vector<std::string> expected = commented_names(glsl);
    EXPECT_EQ(commented_names(hlsl), expected) << "the two examples name their bindings alike";
    // Both kinds of block, with and without an instance name, and what is no block.
    EXPECT_EQ(expected, (std::vector<std::string>{"current_texture", "parameters", "Exposure", "clip_distances"}));

    // Each example completed into a compute shader whose entry point uses every resource (an
    // unused one would not be in the SPIR-V at all).
    const std::string glsl_shader = "#version 450\n#extension GL_EXT_samplerless_texture_functions : require\n"
                                    "layout(local_size_x = 1) in;\n" +
                                    glsl +
                                    "void main() { clip_distances.d[0] = texelFetch(current_texture, ivec2(0), 0).r "
                                    "+ parameters.motion.x + exposure; }\n";
    const std::string hlsl_shader = "struct ResolveParameters { float2 motion; };\n" + hlsl +
                                    "[numthreads(1, 1, 1)] void main() { clip_distances[0] = "
                                    "current_texture.Load(int3(0, 0, 0)).r + parameters.motion.x + exposure; }\n";
    EXPECT_EQ(reflected_names("names.comp", glsl_shader), expected) << glsl_shader;
    EXPECT_EQ(reflected_names("names.cs.hlsl", hlsl_shader), expected) << hlsl_shader;
}

// The engine example's resolves as ported: every binding the GLSL resolve has, its HLSL port has
// under the same name (the port adds the samplers GLSL's combined image samplers held).
TEST(BindingNames, TheEngineExamplesHlslPortsBindTheGlslNames) {
    for (const char* name : {"resolve_compute", "resolve_fragment", "upscale_compute"}) {
        const Variant* glsl = test_shaders::variants().find(name);
        const Variant* hlsl = test_shaders::variants().find((std::string("hlsl_") + name).c_str());
        ASSERT_NE(glsl, nullptr) << name;
        ASSERT_NE(hlsl, nullptr) << name;
        ASSERT_GT(glsl->binding_count, 0u) << name;
        for (std::uint32_t i = 0; i < glsl->binding_count; ++i)
            EXPECT_NE(find_binding(*hlsl, glsl->bindings[i].name), nullptr)
                << "hlsl_" << name << " has no binding '" << glsl->bindings[i].name << "'";
    }
}

} // namespace
} // namespace kdop
