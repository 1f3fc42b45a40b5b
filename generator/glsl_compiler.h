// GLSL (and HLSL) -> SPIR-V with glslang, in-process. Targets Vulkan 1.0 / SPIR-V 1.0 by default so
// the output runs on any Vulkan device (target_env.h for later ones). The module carries OpLine
// debug information so later stages can name source lines.
#pragma once

#include "core/result.h"
#include "generator/declared_resources.h"
#include "generator/target_env.h"

#include <kdop/variant.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

// What `#include "header"` in a shader resolves to: the name messages use for it, and its text.
struct IncludedSource {
    std::string name;
    std::string text;
};
// Resolves `header` as included from the source called `includer`; nullopt when nothing matches.
using IncludeResolver =
    std::function<std::optional<IncludedSource>(std::string_view header, std::string_view includer)>;

// Compiles one compute shader. `name` (e.g. "dop22-clip-n9.comp") prefixes every message, which
// reads "name:LINE: error: ..." followed by the offending source line. With `resolve`, the shader
// may #include other sources (GL_GOOGLE_include_directive, enabled for it as glslc does), each
// looked up through it; errors in an included source name that source. Thread-safe.
Result<std::vector<std::uint32_t>> compile_glsl_compute(std::string_view source, std::string_view name,
                                                        TargetEnv env = TargetEnv::vulkan1_0,
                                                        const IncludeResolver& resolve = {});

// The same for a shader of any stage kdop builds (a project's vertex and fragment SHADERS). With
// `declared`, also every resource the source declares, used or not (declared_resources.h), which
// the SPIR-V alone cannot say.
Result<std::vector<std::uint32_t>> compile_glsl(std::string_view source, std::string_view name, ShaderStage stage,
                                                TargetEnv env = TargetEnv::vulkan1_0,
                                                const IncludeResolver& resolve = {},
                                                std::vector<DeclaredResource>* declared = nullptr);

// Compiles one HLSL compute shader (entry point "main") through glslang's HLSL front end, with
// textures upgraded to combined image samplers; messages as for GLSL. Thread-safe.
Result<std::vector<std::uint32_t>> compile_hlsl_compute(std::string_view source, std::string_view name,
                                                        TargetEnv env = TargetEnv::vulkan1_0);

// A project's HLSL shader of any stage kdop builds, entry point `entry_point`, through glslang's HLSL
// front end, as DXC-based engines write them: Texture2D stays a sampled image and SamplerState a
// sampler; register(t1, space2) becomes set 2, binding 1 (glslang's mapping: the register's number,
// whatever its class, so t0 and s0 collide), and [[vk::binding(1, 2)]] says so explicitly. With
// `resolve`, #include looks up through it; messages as for GLSL; `declared` as for compile_glsl.
// Thread-safe.
Result<std::vector<std::uint32_t>> compile_hlsl(std::string_view source, std::string_view name, ShaderStage stage,
                                                std::string_view entry_point = "main",
                                                TargetEnv env = TargetEnv::vulkan1_0,
                                                const IncludeResolver& resolve = {},
                                                std::vector<DeclaredResource>* declared = nullptr);

// "name:LINE: <message>" and the source line under it, the form every GLSL diagnostic takes.
std::string glsl_diagnostic(std::string_view source, std::string_view name, int line, std::string_view message);

} // namespace kdop
