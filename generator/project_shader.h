// A project's own shader, built at build time with the kdop functions it includes (kdop_add_variants
// SHADERS): a TAA resolve that reprojects, clips with `#include "dop22-clip-n9.glsl"` (or
// "dop22-clip-n9.hlsl") and blends. GLSL by its extension as glslc reads it (.comp, .vert, .frag);
// HLSL by the stage suffix DXC-based engines use (.cs.hlsl, .vs.hlsl, .ps.hlsl). It goes through the same stages as a
// variant (validate, optimize, reflect, drop the line information) and into the same registry, as a Mode::shader entry
// named after its file.
#pragma once

#include "core/result.h"
#include "generator/glsl_compiler.h"
#include "generator/target_env.h"
#include "generator/variant_builder.h"

#include <filesystem>
#include <span>
#include <vector>

namespace kdop {

struct ProjectShader {
    BuiltVariant built;                            // mode shader, name = the file's name without its extensions
    std::vector<std::filesystem::path> read_files; // the shader and every file it included, for a depfile
    std::vector<std::string> warnings;             // lines "<file>: warning: ...": each resource unused
    std::vector<std::string> provided_included;    // the names of options.provided the shader included
};

struct ProjectShaderOptions {
    std::vector<std::filesystem::path> include_dirs; // where other includes are looked up, in order
    TargetEnv env = TargetEnv::vulkan1_0;
    bool strip_names = false;              // drop OpName and OpMemberName
    std::string hlsl_entry_point = "main"; // of every HLSL shader (a GLSL shader's is main)
    // Headers given by name, looked up before the variants and the files: kdop taa --resolve's
    // "kdop_variant.glsl", the variant under test behind a name that does not change.
    std::vector<IncludedSource> provided = {};
};

// Where a shader file's stage, language and registry name come from: its extensions.
struct ShaderFile {
    ShaderStage stage;
    bool hlsl;
    std::string name; // "resolve" for resolve.comp and resolve.cs.hlsl
};
// Fails, naming the file, for a stage kdop does not build (a geometry shader, .geom or .gs.hlsl)
// and for an extension that says no stage.
Result<ShaderFile> shader_file_kind(const std::filesystem::path& file);

// Compiles `file`. `#include "<variant>.glsl"` (in HLSL, "<variant>.hlsl") names the includable
// function of one of `variants`; any other include is looked up next to the including file, then
// in the include directories, in order. Loops are allowed: this is the project's code, not a
// variant. SPIR-V for `options.env`. A resource the shader declares and its entry point does not
// use is in built.unused_resources, with a warning naming it.
Result<ProjectShader> build_project_shader(const std::filesystem::path& file, std::span<const BuiltVariant> variants,
                                           const ProjectShaderOptions& options = {});

// A Makefile rule "<target>: <dependencies>" (spaces, '#', '\\' and '$' escaped), the depfile format
// CMake and Ninja read. A path with a line break, which the format cannot hold, is refused.
Result<std::string> depfile_rule(const std::filesystem::path& target,
                                 std::span<const std::filesystem::path> dependencies);

} // namespace kdop
