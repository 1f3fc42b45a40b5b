#include "generator/project_shader.h"

#include "core/read_file.h"
#include "core/shown_text.h"
#include "generator/glsl_compiler.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace kdop {
namespace fs = std::filesystem;

namespace {

// Whether `file` lies in `folder` or below it, links and ".." resolved.
bool is_inside(const fs::path& file, const fs::path& folder) {
    std::error_code ec;
    const fs::path f = fs::weakly_canonical(file, ec);
    const fs::path d = fs::weakly_canonical(folder.empty() ? fs::path(".") : folder, ec);
    if (ec) return false;
    auto [end, _] = std::mismatch(d.begin(), d.end(), f.begin(), f.end());
    return end == d.end();
}

// The stage glslc reads from the extension; what kdop does not build pipelines for, refused by name.
Result<ShaderStage> stage_of_file(const fs::path& file) {
    const std::string extension = file.extension().string();
    if (extension == ".comp") return ShaderStage::compute;
    if (extension == ".vert") return ShaderStage::vertex;
    if (extension == ".frag") return ShaderStage::fragment;
    static const std::pair<const char*, const char*> others[] = {{".geom", "a geometry"},
                                                                 {".tesc", "a tessellation control"},
                                                                 {".tese", "a tessellation evaluation"},
                                                                 {".mesh", "a mesh"},
                                                                 {".task", "a task"},
                                                                 {".rgen", "a ray generation"},
                                                                 {".rchit", "a closest-hit"},
                                                                 {".rahit", "an any-hit"},
                                                                 {".rmiss", "a miss"},
                                                                 {".rint", "an intersection"},
                                                                 {".rcall", "a callable"}};
    for (const auto& [other, stage] : others)
        if (extension == other)
            return fail(fmt::format("{}: '{}' is {} shader; kdop builds compute (.comp), vertex (.vert) and fragment "
                                    "(.frag) shaders",
                                    file.string(), extension, stage));
    return fail(fmt::format("{}: the stage is read from the extension, as glslc reads it: .comp, .vert or .frag",
                            file.string()));
}

} // namespace

Result<ProjectShader> build_project_shader(const fs::path& file, std::span<const BuiltVariant> variants,
                                           std::span<const fs::path> include_dirs, TargetEnv env, bool strip_names) {
    ProjectShader out;
    out.built.spec.mode = Mode::shader;
    out.built.name = file.stem().string();
    const std::string name = file.string();
    auto stage = stage_of_file(file);
    if (!stage) return std::unexpected(stage.error());
    auto source = read_file(file);
    if (!source) return fail(fmt::format("{}: cannot read shader", name));
    out.built.compute_glsl = std::move(*source);
    out.read_files.push_back(fs::absolute(file));

    // Included sources are named by their path (or "<variant>.glsl"), so messages point at them.
    // A file is included only from inside the including file's folder or an include directory: a
    // shader cannot read "/etc/passwd" or "../../../secret" into a build.
    std::vector<std::string> unresolved, outside;
    IncludeResolver resolve = [&](std::string_view header, std::string_view includer) -> std::optional<IncludedSource> {
        for (const BuiltVariant& v : variants)
            if (header == v.name + ".glsl") return IncludedSource{std::string(header), v.function(kGlsl)};
        std::vector<fs::path> folders{fs::path(includer).parent_path()};
        folders.insert(folders.end(), include_dirs.begin(), include_dirs.end());
        for (const fs::path& folder : folders) {
            const fs::path candidate = folder / header;
            if (!fs::exists(candidate)) continue;
            if (!is_inside(candidate, folder)) {
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
    out.built.spec.target_env = env;
    out.built.spec.strip_names = strip_names;
    auto compiled = compile_glsl(out.built.compute_glsl, name, *stage, env, resolve);
    if (!compiled && !outside.empty()) return fail(compiled.error().message + outside.front());
    if (!compiled && !unresolved.empty()) {
        std::vector<std::string> functions;
        for (const BuiltVariant& v : variants) functions.push_back(v.name + ".glsl");
        return fail(fmt::format("{}{}: \"{}\" is neither a selected variant's function ({}) nor a file next to the "
                                "including one or in an include directory\n",
                                compiled.error().message, name, unresolved.front(), fmt::join(functions, ", ")));
    }
    if (auto ok = compile_into(out.built, out.built.compute_glsl, name, env, std::move(compiled)); !ok)
        return std::unexpected(ok.error());
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
