// kdop-gen: the build-time half of kdop. kdop_add_variants() runs `kdop-gen registry` to embed
// variants in a target; the refresh-generated target runs `kdop-gen glsl` to rewrite generated/,
// and a test runs `kdop-gen glsl --check` to catch a stale generated/.
#include "core/read_file.h"
#include "core/shown_text.h"
#include "core/utf8.h"
#include "generator/command_line.h"
#include "generator/project_shader.h"
#include "generator/reflection_json.h"
#include "generator/registry_writer.h"
#include "generator/selection_options.h"
#include "generator/variant_builder.h"
#include "generator/variant_files.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <set>

namespace fs = std::filesystem;
using namespace kdop;

namespace {

int report(const Error& error) {
    std::cerr << "kdop-gen: " << terminal_text(error.message) << (error.message.ends_with('\n') ? "" : "\n");
    return 1;
}

// Rewrites `dir` with the default variants' GLSL and HLSL, removing such files no default variant has; with
// `check`, writes nothing and fails when any file would change.
int glsl_directory(const std::vector<BuiltVariant>& built, const fs::path& dir, bool check) {
    std::vector<OutputFile> files;
    std::set<fs::path> expected;
    for (const BuiltVariant& v : built)
        for (OutputFile& f : glsl_files(v, dir)) {
            expected.insert(f.path);
            files.push_back(std::move(f));
        }
    std::vector<fs::path> extra;
    if (fs::is_directory(dir))
        for (const auto& entry : fs::directory_iterator(dir)) {
            const auto ext = entry.path().extension().string();
            const bool generated =
                ext == ".comp" ||
                std::ranges::any_of(kShaderLanguages, [&](const ShaderLanguage& l) { return l.extension == ext; });
            if (generated && !expected.count(entry.path())) extra.push_back(entry.path());
        }
    std::sort(extra.begin(), extra.end());

    if (check) {
        int stale = 0;
        for (const OutputFile& f : files)
            if (read_file(f.path) != f.content) { // missing, unreadable or different
                std::cerr << terminal_text(f.path.string()) << ": stale or missing\n";
                ++stale;
            }
        for (const fs::path& p : extra) {
            std::cerr << terminal_text(p.string()) << ": no default variant generates this file\n";
            ++stale;
        }
        if (stale)
            std::cerr << fmt::format(
                "{} generated file(s) out of date; run `cmake --build build --target refresh-generated`\n", stale);
        return stale ? 1 : 0;
    }
    if (auto ok = write_files_atomically(files); !ok) return report(ok.error());
    for (const fs::path& p : extra) fs::remove(p);
    std::cout << fmt::format("kdop-gen: wrote {} files to {}\n", files.size(), dir.string());
    return 0;
}

// How the JSON `json` names the file `file_name` in `spirv_dir`: by its path from the JSON's folder
// where there is one, else by its absolute path.
std::string spirv_path_in_json(const fs::path& spirv_dir, const fs::path& json, const std::string& file_name) {
    const fs::path file = fs::absolute(fs::path(spirv_dir) / file_name).lexically_normal();
    const fs::path relative = file.lexically_relative(fs::absolute(json).parent_path());
    return (relative.empty() ? file : relative).generic_string();
}

// `kdop-gen registry`'s options.
struct RegistryOptions {
    SelectionOptions selection;
    std::string header, source, cpp_namespace; // the C++ registry
    std::string json, spirv_dir;               // its reflection, and the SPIR-V the JSON names
    std::string functions_dir, depfile, hlsl_entry = "main";
    std::vector<std::string> shaders, include_dirs;
};

// Whether `name` can be an HLSL entry point: an identifier.
std::string hlsl_function_name_problem(const std::string& name) {
    const bool identifier =
        !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0])) &&
        std::ranges::all_of(name, [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
    return identifier ? std::string() : "'" + terminal_text(name) + "' is not an HLSL function name";
}

CLI::App* add_registry_command(CLI::App& app, RegistryOptions& o) {
    CLI::App* registry = app.add_subcommand(
        "registry", "Write a C++ registry (header + source) of the selected variants, or their reflection as JSON, "
                    "or both");
    o.selection.add_to(*registry, /*with_manifest=*/true);
    registry->add_option("--header", o.header, "Header file to write (with --source and --namespace)");
    registry->add_option("--source", o.source, "Source file to write");
    registry->add_option("--namespace", o.cpp_namespace, "C++ namespace of the registry");
    registry->add_option("--json", o.json,
                         "Write every entry's reflection as JSON to this file (docs/reflection.schema.json), for "
                         "engines and builds that do not read C++");
    registry->add_option("--spirv-dir", o.spirv_dir,
                         "Also write each entry's SPIR-V as <name>.spv into this directory, named in the JSON");
    registry->add_option(
        "--functions", o.functions_dir,
        "Also write each selected variant's includable function (<variant>.glsl, .hlsl, .wgsl) into this "
        "directory");
    registry
        ->add_option("--shaders", o.shaders,
                     "The project's own shaders to embed too, GLSL (.comp, .vert, .frag) or HLSL (.cs.hlsl, "
                     ".vs.hlsl, .ps.hlsl), named after their files; `#include \"<variant>.glsl\"` (or .hlsl) gives "
                     "them a selected variant's function")
        ->check(CLI::ExistingFile);
    registry->add_option("--hlsl-entry", o.hlsl_entry, "The entry point of the HLSL shaders (DXC's -E)")
        ->capture_default_str()
        ->check(hlsl_function_name_problem, "IDENTIFIER");
    registry->add_option("--include-dirs", o.include_dirs, "Where the shaders' other includes are looked up")
        ->check(CLI::ExistingDirectory);
    registry->add_option("--depfile", o.depfile, "Write the files the shaders read as a depfile for the header");
    return registry;
}

// What is wrong with the registry's options together, before anything is built: what to write,
// and where.
std::optional<std::string> registry_problem(const RegistryOptions& o) {
    const bool cpp = !o.header.empty() || !o.source.empty() || !o.cpp_namespace.empty();
    if (cpp && (o.header.empty() || o.source.empty() || o.cpp_namespace.empty()))
        return "the C++ registry takes --header, --source and --namespace together";
    if (!cpp && o.json.empty())
        return "nothing to write: give --header, --source and --namespace (the C++ registry), --json FILE "
               "(its reflection), or both";
    if (!o.spirv_dir.empty() && o.json.empty()) return "--spirv-dir writes the files the JSON names; give --json too";
    if (auto problem = registry_files_problem(o.header, o.source, o.depfile, o.json)) return problem;
    // The JSON names each .spv file by its path; JSON holds only UTF-8.
    if (!o.spirv_dir.empty())
        if (const std::string named = spirv_path_in_json(o.spirv_dir, o.json, "x.spv"); first_non_utf8_byte(named))
            return fmt::format("--spirv-dir: the JSON would name its files as '{}', which is not UTF-8, "
                               "and JSON holds nothing else; name a folder whose path is UTF-8",
                               shown_text(named, 300));
    if (cpp)
        if (auto why = cpp_namespace_problem(o.cpp_namespace))
            return fmt::format("--namespace: '{}' {}", shown_text(o.cpp_namespace), *why);
    return std::nullopt;
}

// The project's shaders built with the variants' functions and appended to `built`; the files they
// read, for the depfile.
Result<std::vector<fs::path>> add_project_shaders(const RegistryOptions& o, std::vector<BuiltVariant>& built) {
    std::vector<fs::path> reads;
    const ProjectShaderOptions shader_options{
        .include_dirs = {o.include_dirs.begin(), o.include_dirs.end()},
        .env = *parse_target_env(o.selection.target_env), // checked by CLI11
        .strip_names = o.selection.strip_names,
        .hlsl_entry_point = o.hlsl_entry,
    };
    const std::size_t variant_count = built.size();
    for (const std::string& file : o.shaders) {
        auto shader = build_project_shader(file, std::span(built.data(), variant_count), shader_options);
        if (!shader) return std::unexpected(shader.error());
        for (const std::string& warning : shader->warnings) std::cerr << "kdop-gen: " << terminal_text(warning);
        for (const BuiltVariant& v : built)
            if (v.name == shader->built.name)
                return fail(fmt::format("{}: a shader named '{}' would hide the variant or shader of that name; "
                                        "rename the file",
                                        file, v.name));
        reads.insert(reads.end(), shader->read_files.begin(), shader->read_files.end());
        built.push_back(std::move(shader->built));
    }
    return reads;
}

// The C++ registry and the JSON of `built`, each where the options say, with the .spv files the
// JSON names.
void add_registry_files(const RegistryOptions& o, const std::vector<BuiltVariant>& built,
                        const std::optional<ResolveSettings>& resolve, std::vector<OutputFile>& files) {
    if (!o.header.empty()) {
        auto sources = write_registry(built, o.cpp_namespace, fs::path(o.header).filename().string(), resolve);
        files.push_back({o.header, sources.header});
        files.push_back({o.source, sources.source});
    }
    if (o.json.empty()) return;
    // Each .spv as the JSON's folder reaches it.
    std::function<std::optional<std::string>(const BuiltVariant&)> spirv_name;
    if (!o.spirv_dir.empty()) {
        for (const BuiltVariant& v : built) files.push_back(spirv_file(v, o.spirv_dir));
        spirv_name = [&](const BuiltVariant& v) {
            return std::optional(spirv_path_in_json(o.spirv_dir, o.json, v.name + ".spv"));
        };
    }
    files.push_back({o.json, reflection_json(built, spirv_name, resolve)});
}

// Every file `kdop-gen registry` writes, as one set: the functions, the depfile, the registry.
int write_registry_outputs(const RegistryOptions& o, std::vector<BuiltVariant>& built,
                           const std::optional<ResolveSettings>& resolve) {
    std::vector<OutputFile> files;
    if (!o.functions_dir.empty())
        for (const BuiltVariant& v : built)
            for (OutputFile& f : function_files(v, o.functions_dir)) files.push_back(std::move(f));
    auto shader_reads = add_project_shaders(o, built);
    if (!shader_reads) return report(shader_reads.error());
    if (!o.depfile.empty()) {
        auto rule = depfile_rule(o.header.empty() ? o.json : o.header, *shader_reads);
        if (!rule) return report(rule.error());
        files.push_back({o.depfile, *rule});
    }
    add_registry_files(o, built, resolve, files);
    if (auto ok = write_files_atomically(files); !ok) return report(ok.error());
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"kdop-gen: generate k-DOP clipping variants at build time"};
    app.require_subcommand(1);
    RegistryOptions options;
    CLI::App* registry = add_registry_command(app, options);
    std::string glsl_dir;
    bool check = false;
    CLI::App* glsl =
        app.add_subcommand("glsl", "Write every default variant's .glsl, .hlsl, .wgsl and .comp into a directory");
    glsl->add_option("--out", glsl_dir, "Directory (normally generated/)")->required();
    glsl->add_flag("--check", check, "Write nothing; fail if any file in the directory is stale");

    return run_command_line(app, "kdop-gen", argc, argv, [&] {
        if (*registry)
            if (auto problem = registry_problem(options)) {
                report({*problem});
                return kUsageError;
            }
        auto specs = *registry ? options.selection.select() : select_variants({}, {}, {});
        if (!specs) return report(specs.error());
        auto resolve = *registry ? options.selection.resolve() : std::optional<ResolveSettings>();
        if (!resolve) return report(resolve.error());
        auto built = build_variants(*specs);
        if (!built) return report(built.error());
        if (*glsl) return glsl_directory(*built, glsl_dir, check);
        return write_registry_outputs(options, *built, *resolve);
    });
}
