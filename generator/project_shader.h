// A project's own shader (compute, vertex or fragment, by its extension), built at build time with
// the kdop functions it includes (kdop_add_variants SHADERS): a TAA resolve that reprojects, clips with
// `#include "dop22-clip-n9.glsl"` and blends. It goes through the same stages as a variant
// (validate, optimize, reflect, drop the line information) and into the same registry, as a Mode::shader entry named
// after its file.
#pragma once

#include "core/result.h"
#include "generator/target_env.h"
#include "generator/variant_builder.h"

#include <filesystem>
#include <span>
#include <vector>

namespace kdop {

struct ProjectShader {
    BuiltVariant built;                            // mode shader, name = the file's stem
    std::vector<std::filesystem::path> read_files; // the shader and every file it included, for a depfile
};

// Compiles `file`. `#include "<variant>.glsl"` names the includable function of one of `variants`;
// any other include is looked up next to the including file, then in `include_dirs`, in order.
// Loops are allowed: this is the project's code, not a variant. SPIR-V for `env`, with its names
// unless `strip_names`.
Result<ProjectShader> build_project_shader(const std::filesystem::path& file, std::span<const BuiltVariant> variants,
                                           std::span<const std::filesystem::path> include_dirs,
                                           TargetEnv env = TargetEnv::vulkan1_0, bool strip_names = false);

// A Makefile rule "<target>: <dependencies>" (spaces, '#', '\\' and '$' escaped), the depfile format
// CMake and Ninja read. A path with a line break, which the format cannot hold, is refused.
Result<std::string> depfile_rule(const std::filesystem::path& target,
                                 std::span<const std::filesystem::path> dependencies);

} // namespace kdop
