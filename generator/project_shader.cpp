#include "generator/project_shader.h"

#include "core/read_file.h"
#include "core/shown_text.h"
#include "core/utf8.h"
#include "generator/glsl_compiler.h"
#include "generator/inside_folder.h"
#include "generator/unused_resources.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <optional>
#include <string_view>

namespace kdop {
namespace fs = std::filesystem;

namespace {

// The two failures every HLSL port meets first, and why, where `message` is one; else nothing.
std::string hlsl_port_note(const std::string& message, const std::string& name, TargetEnv env) {
    if (message.find(" share set ") != std::string::npos)
        return fmt::format("{}: glslang makes a register's number its binding whatever its class, so t0 and s0 "
                           "collide, and a resource without a register is binding 0; number them apart "
                           "(register(s1)) or give [[vk::binding(binding, set)]]\n",
                           name);
    if (env == TargetEnv::vulkan1_0 && message.find("buffer layout rules") != std::string::npos)
        return fmt::format("{}: HLSL packs a constant buffer tighter than Vulkan 1.0 allows (a float2 after a float "
                           "shares its 16 bytes); TARGET_ENV vulkan1.1 or later (--target-env) takes HLSL's packing, "
                           "or order or pad the members as std140 does\n",
                           name);
    return {};
}

// The suffixes a shader's stage is read from: glslc's extensions, and the stage before .hlsl that
// DXC-based engines write (taa_resolve.cs.hlsl). A stage kdop makes no pipelines of is named.
struct StageSuffix {
    const char* suffix;
    std::optional<ShaderStage> stage; // none: refused
    const char* what;
};
constexpr StageSuffix kStageSuffixes[] = {
    {".comp", ShaderStage::compute, "a compute"},
    {".vert", ShaderStage::vertex, "a vertex"},
    {".frag", ShaderStage::fragment, "a fragment"},
    {".geom", std::nullopt, "a geometry"},
    {".tesc", std::nullopt, "a tessellation control"},
    {".tese", std::nullopt, "a tessellation evaluation"},
    {".mesh", std::nullopt, "a mesh"},
    {".task", std::nullopt, "a task"},
    {".rgen", std::nullopt, "a ray generation"},
    {".rchit", std::nullopt, "a closest-hit"},
    {".rahit", std::nullopt, "an any-hit"},
    {".rmiss", std::nullopt, "a miss"},
    {".rint", std::nullopt, "an intersection"},
    {".rcall", std::nullopt, "a callable"},
    {".cs.hlsl", ShaderStage::compute, "a compute"},
    {".vs.hlsl", ShaderStage::vertex, "a vertex"},
    {".ps.hlsl", ShaderStage::fragment, "a pixel"},
    {".gs.hlsl", std::nullopt, "a geometry"},
    {".hs.hlsl", std::nullopt, "a hull"},
    {".ds.hlsl", std::nullopt, "a domain"},
    {".ms.hlsl", std::nullopt, "a mesh"},
    {".as.hlsl", std::nullopt, "an amplification"},
    {".lib.hlsl", std::nullopt, "a library"},
};

// Why `name`, a shader's file name less its stage suffix, cannot be its registry entry's name, or
// nothing. The registry (C++ and JSON) holds any UTF-8 name as it is, but JSON holds nothing else,
// and `..comp` became an entry named '.', whose SPIR-V file (--spirv-dir) is "..spv".
std::optional<std::string> registry_name_problem(std::string_view name) {
    if (auto at = first_non_utf8_byte(name))
        return fmt::format("whose byte 0x{:02x} is not UTF-8, which the registry's JSON cannot hold",
                           static_cast<unsigned char>(name[*at]));
    if (name.starts_with('.'))
        return "which begins with '.': a name of dots names no shader, and <name>.spv would be a hidden file";
    return std::nullopt;
}

} // namespace

Result<ShaderFile> shader_file_kind(const fs::path& file) {
    const std::string file_name = file.filename().string();
    for (const StageSuffix& s : kStageSuffixes) {
        const std::string_view suffix = s.suffix;
        if (file_name.size() <= suffix.size() || !file_name.ends_with(suffix)) continue;
        if (!s.stage)
            return fail(fmt::format("{}: '{}' is {} shader; kdop builds compute (.comp, .cs.hlsl), vertex (.vert, "
                                    ".vs.hlsl) and fragment (.frag, .ps.hlsl) shaders",
                                    file.string(), suffix, s.what));
        ShaderFile kind{*s.stage, suffix.ends_with(".hlsl"), file_name.substr(0, file_name.size() - suffix.size())};
        if (auto why = registry_name_problem(kind.name))
            return fail(fmt::format("{}: the registry would name this shader '{}', {}; rename the file",
                                    shown_text(file.string(), 300), shown_text(kind.name), *why));
        return kind;
    }
    if (file.extension() == ".hlsl")
        return fail(fmt::format("{}: an HLSL shader's stage is read from the suffix before .hlsl, as DXC-based engines "
                                "name them: .cs.hlsl, .vs.hlsl or .ps.hlsl",
                                file.string()));
    return fail(fmt::format("{}: the stage is read from the extension, as glslc reads it (.comp, .vert or .frag), or "
                            "for HLSL from the suffix before .hlsl (.cs.hlsl, .vs.hlsl or .ps.hlsl)",
                            file.string()));
}

Result<ProjectShader> build_project_shader(const fs::path& file, std::span<const BuiltVariant> variants,
                                           const ProjectShaderOptions& options) {
    ProjectShader out;
    out.built.spec.mode = Mode::shader;
    const std::string name = file.string();
    auto kind = shader_file_kind(file);
    if (!kind) return std::unexpected(kind.error());
    out.built.name = kind->name;
    // The language whose functions the shader includes: "<variant>.glsl" or "<variant>.hlsl".
    const ShaderLanguage& language = shader_language(kind->hlsl ? kHlsl : kGlsl);
    auto source = read_file(file);
    if (!source) return fail(fmt::format("{}: cannot read shader", name));
    // The source as written: GLSL in compute_glsl, HLSL in compute_hlsl, whatever its stage.
    std::string& text = kind->hlsl ? out.built.compute_hlsl : out.built.compute_glsl;
    text = std::move(*source);
    out.read_files.push_back(fs::absolute(file));

    // Included sources are named by their path (or "<variant>.glsl"), so messages point at them.
    // A file is included only from inside the including file's folder or an include directory: a
    // shader cannot read "/etc/passwd" or "../../../secret" into a build.
    std::vector<std::string> unresolved, outside;
    IncludeResolver resolve = [&](std::string_view header, std::string_view includer) -> std::optional<IncludedSource> {
        for (const IncludedSource& given : options.provided)
            if (header == given.name) {
                out.provided_included.push_back(given.name);
                return given;
            }
        for (const BuiltVariant& v : variants)
            if (header == std::string(v.name).append(language.extension))
                return IncludedSource{std::string(header), v.function(*language.dialect)};
        std::vector<fs::path> folders{fs::path(includer).parent_path()};
        folders.insert(folders.end(), options.include_dirs.begin(), options.include_dirs.end());
        for (const fs::path& folder : folders) {
            const fs::path candidate = folder / header;
            if (!fs::exists(candidate)) continue;
            if (!is_inside_folder(candidate, folder)) {
                outside.push_back(fmt::format("{}: #include \"{}\" names {}, which is outside {}; kdop includes "
                                              "only from the including file's folder and the include directories\n",
                                              includer, header, candidate.lexically_normal().string(),
                                              folder.empty() ? "the current folder" : folder.string()));
                continue;
            }
            if (auto text = read_file(candidate)) {
                out.read_files.push_back(fs::absolute(candidate));
                return IncludedSource{candidate.string(), std::move(*text)};
            }
        }
        unresolved.emplace_back(header);
        return std::nullopt;
    };
    const TargetEnv env = options.env;
    out.built.spec.target_env = env;
    out.built.spec.strip_names = options.strip_names;
    std::vector<DeclaredResource> declared;
    auto compiled = kind->hlsl
                        ? compile_hlsl(text, name, kind->stage, options.hlsl_entry_point, env, resolve, &declared)
                        : compile_glsl(text, name, kind->stage, env, resolve, &declared);
    if (!compiled && !outside.empty()) return fail(compiled.error().message + outside.front());
    if (!compiled && !unresolved.empty()) {
        std::vector<std::string> functions;
        for (const BuiltVariant& v : variants) functions.push_back(std::string(v.name).append(language.extension));
        return fail(fmt::format("{}{}: \"{}\" is neither a selected variant's function ({}) nor a file next to the "
                                "including one or in an include directory\n",
                                compiled.error().message, name, unresolved.front(), fmt::join(functions, ", ")));
    }
    if (auto ok = compile_into(out.built, text, name, env, std::move(compiled)); !ok) {
        if (!kind->hlsl) return std::unexpected(ok.error());
        std::string message = ok.error().message;
        if (!message.ends_with('\n')) message += '\n';
        return fail(message + hlsl_port_note(message, name, env));
    }
    out.built.unused_resources = unused_resources(declared, out.built.interface);
    for (const DeclaredResource& r : out.built.unused_resources)
        out.warnings.push_back(unused_resource_warning(name, out.built.interface.entry_point, r));
    return out;
}

Result<std::string> depfile_rule(const fs::path& target, std::span<const fs::path> dependencies) {
    std::vector<fs::path> paths(dependencies.begin(), dependencies.end());
    paths.push_back(target);
    for (const fs::path& p : paths)
        if (p.string().find_first_of("\n\r") != std::string::npos)
            return fail(fmt::format("{}: a line break in a file's path cannot be written in a depfile; rename it",
                                    shown_text(p.string())));
    auto escaped = [](const fs::path& p) {
        std::string out;
        for (char c : p.string()) {
            if (c == ' ' || c == '#' || c == '\\') out += '\\';
            if (c == '$') out += '$';
            out += c;
        }
        return out;
    };
    std::string rule = escaped(target) + ":";
    for (const fs::path& d : dependencies) rule += " \\\n  " + escaped(d);
    return rule + "\n";
}

} // namespace kdop
