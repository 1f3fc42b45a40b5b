#include "generator/glsl_compiler.h"

#include "generator/glslang_includer.h"
#include "generator/source_names.h"

#include <fmt/format.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <mutex>
#include <optional>
#include <regex>
#include <string>
#include <utility>

namespace kdop {
namespace {

void initialize_glslang_once() {
    static std::once_flag once;
    std::call_once(once, [] { glslang::InitializeProcess(); });
}

std::string_view source_line(std::string_view source, int line) {
    for (int l = 1; l < line && !source.empty(); ++l) {
        size_t eol = source.find('\n');
        source = eol == std::string_view::npos ? std::string_view{} : source.substr(eol + 1);
    }
    return source.substr(0, source.find('\n'));
}

// glslang logs "ERROR: name:12: 'x' : undeclared identifier", where name is glslang's for the source
// (source_names.h); rewrite each such line as a diagnostic naming the real source, with the source
// line where it is the shader's own, and keep any other text as it is.
std::string rewrite_log(std::string_view log, std::string_view source, std::string_view name,
                        const SourceNames& names) {
    static const std::regex located(R"(^(ERROR|WARNING): ([^:]*):(\d+): (.*)$)");
    std::string out;
    std::string text(log);
    size_t start = 0;
    while (start < text.size()) {
        size_t eol = text.find('\n', start);
        std::string line = text.substr(start, eol == std::string::npos ? std::string::npos : eol - start);
        start = eol == std::string::npos ? text.size() : eol + 1;
        std::smatch m;
        if (line.find("compilation terminated") != std::string::npos) continue; // follows an error already shown
        if (std::regex_match(line, m, located)) {
            std::string severity = m[1] == "ERROR" ? "error" : "warning";
            const std::string file = names.real(m[2].str());
            if (file == name)
                out += glsl_diagnostic(source, name, std::stoi(m[3]), severity + ": " + m[4].str());
            else // in an included source, whose text is not at hand here
                out += fmt::format("{}:{}: {}: {}\n", file, m[3].str(), severity, m[4].str());
        } else if (!line.empty() && line.find("compilation errors") == std::string::npos) {
            out += fmt::format("{}: {}\n", name, line);
        }
    }
    return out;
}

// glslang's client and SPIR-V target for `env` (target_env.h).
std::pair<glslang::EShTargetClientVersion, glslang::EShTargetLanguageVersion> glslang_target(TargetEnv env) {
    switch (env) {
    case TargetEnv::vulkan1_0: return {glslang::EShTargetVulkan_1_0, glslang::EShTargetSpv_1_0};
    case TargetEnv::vulkan1_1: return {glslang::EShTargetVulkan_1_1, glslang::EShTargetSpv_1_3};
    case TargetEnv::vulkan1_2: return {glslang::EShTargetVulkan_1_2, glslang::EShTargetSpv_1_5};
    case TargetEnv::vulkan1_3: return {glslang::EShTargetVulkan_1_3, glslang::EShTargetSpv_1_6};
    }
    return {glslang::EShTargetVulkan_1_0, glslang::EShTargetSpv_1_0};
}

// Compiles one compute shader of `language` for `env`: parse, link, translate to SPIR-V. With a
// resolver, #include works as with glslc (GL_GOOGLE_include_directive, enabled); without one, an
// #include is an error.
EShLanguage glslang_stage(ShaderStage stage) {
    switch (stage) {
    case ShaderStage::compute: return EShLangCompute;
    case ShaderStage::vertex: return EShLangVertex;
    case ShaderStage::fragment: return EShLangFragment;
    }
    return EShLangCompute;
}

// How an HLSL source's textures reach SPIR-V: as combined image samplers (kdop's own HLSL compute
// shader, bound as the GLSL one is) or as written (a project's Texture2D and SamplerState).
enum class HlslTextures { combined, separate };

struct CompileRequest {
    glslang::EShSource language = glslang::EShSourceGlsl;
    ShaderStage stage = ShaderStage::compute;
    std::string entry_point = "main"; // HLSL; GLSL's is always main
    HlslTextures textures = HlslTextures::combined;
    std::vector<DeclaredResource>* declared = nullptr; // filled from the syntax tree, where given
};

Result<std::vector<std::uint32_t>> compile_shader(const CompileRequest& request, std::string_view source,
                                                  std::string_view name, TargetEnv env,
                                                  const IncludeResolver& resolve = {}) {
    const glslang::EShSource language = request.language;
    const EShLanguage stage = glslang_stage(request.stage);
    initialize_glslang_once();
    const bool hlsl = language == glslang::EShSourceHlsl;
    int flags = EShMsgSpvRules | EShMsgVulkanRules;
    if (hlsl) flags |= EShMsgReadHlsl;
    const EShMessages messages = static_cast<EShMessages>(flags);

    glslang::TShader shader(stage);
    const char* text = source.data();
    const int length = static_cast<int>(source.size());
    SourceNames names;
    const char* glslang_name = names.alias(std::string(name)).c_str();
    shader.setStringsWithLengthsAndNames(&text, &length, &glslang_name, 1);
    const auto [client, target] = glslang_target(env);
    shader.setEnvInput(language, stage, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, client);
    shader.setEnvTarget(glslang::EShTargetSpv, target);
    if (hlsl) {
        // Registers become bindings as glslang maps them: register(t1, space2) is set 2, binding 1,
        // whatever its class, and [[vk::binding(b, s)]] overrides it.
        shader.setEntryPoint(request.entry_point.c_str());
        // HLSL textures are separate images; for kdop's own compute shader this turns each into a
        // combined image sampler (and drops sampler objects), the descriptor type the GLSL shader's
        // sampler2D has and the runtime binds.
        if (request.textures == HlslTextures::combined)
            shader.setTextureSamplerTransformMode(EShTexSampTransUpgradeTextureRemoveSampler);
    }

    std::optional<GlslangIncluder> includer;
    glslang::TShader::ForbidIncluder no_includes;
    if (resolve) {
        if (!hlsl) shader.setPreamble("#extension GL_GOOGLE_include_directive : enable\n"); // HLSL has #include
        includer.emplace(resolve, names);
    }
    glslang::TShader::Includer& chosen = includer ? static_cast<glslang::TShader::Includer&>(*includer) : no_includes;
    const bool parsed = shader.parse(GetDefaultResources(), 450, false, messages, chosen);
    if (includer && !includer->too_much().empty()) return fail(includer->too_much());
    if (!parsed)
        return fail((includer ? includer->too_deep() : "") + rewrite_log(shader.getInfoLog(), source, name, names));

    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages)) return fail(rewrite_log(program.getInfoLog(), source, name, names));
    // glslang only warns when an HLSL entry point is missing, and makes an empty one.
    if (hlsl && std::string_view(program.getInfoLog()).find("Entry point not found") != std::string_view::npos)
        return fail(fmt::format("{}: no function '{}', the entry point; name another with HLSL_ENTRY "
                                "(kdop-gen --hlsl-entry)\n",
                                name, request.entry_point));

    // The tree has every resource declared; the SPIR-V made from it has, for HLSL, only those the
    // entry point reaches.
    if (request.declared) *request.declared = declared_resources(*program.getIntermediate(stage));

    std::vector<std::uint32_t> words;
    spv::SpvBuildLogger logger;
    glslang::SpvOptions options;
    options.generateDebugInfo = true; // OpLine, so validator messages can name GLSL lines
    options.disableOptimizer = true;  // SPIRV-Tools optimizes in the next stage, with our settings
    glslang::GlslangToSpv(*program.getIntermediate(stage), words, &logger, &options);
    std::string spv_messages = logger.getAllMessages();
    if (words.empty() || !spv_messages.empty())
        return fail(fmt::format("{}: SPIR-V generation failed: {}", name, spv_messages));
    return words;
}

} // namespace

std::string glsl_diagnostic(std::string_view source, std::string_view name, int line, std::string_view message) {
    if (line <= 0) return fmt::format("{}: {}\n", name, message);
    return fmt::format("{}:{}: {}\n    {}\n", name, line, message, source_line(source, line));
}

Result<std::vector<std::uint32_t>> compile_glsl_compute(std::string_view source, std::string_view name, TargetEnv env,
                                                        const IncludeResolver& resolve) {
    return compile_shader({}, source, name, env, resolve);
}

Result<std::vector<std::uint32_t>> compile_glsl(std::string_view source, std::string_view name, ShaderStage stage,
                                                TargetEnv env, const IncludeResolver& resolve,
                                                std::vector<DeclaredResource>* declared) {
    return compile_shader({.stage = stage, .declared = declared}, source, name, env, resolve);
}

Result<std::vector<std::uint32_t>> compile_hlsl_compute(std::string_view source, std::string_view name, TargetEnv env) {
    return compile_shader({.language = glslang::EShSourceHlsl}, source, name, env);
}

Result<std::vector<std::uint32_t>> compile_hlsl(std::string_view source, std::string_view name, ShaderStage stage,
                                                std::string_view entry_point, TargetEnv env,
                                                const IncludeResolver& resolve,
                                                std::vector<DeclaredResource>* declared) {
    const CompileRequest request{glslang::EShSourceHlsl, stage, std::string(entry_point), HlslTextures::separate,
                                 declared};
    return compile_shader(request, source, name, env, resolve);
}

} // namespace kdop
