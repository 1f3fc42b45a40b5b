#include "generator/registry_writer.h"

#include "core/escaped_text.h"
#include "core/input_files.h"
#include "core/shown_text.h"
#include "core/upscale_settings.h"
#include "core/write_files.h"
#include "generator/manifest.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <optional>
#include <regex>
#include <set>

#ifndef KDOP_VERSION
#error "KDOP_VERSION must be defined by the build"
#endif

namespace kdop {
namespace {

std::string cpp_enum(DescriptorType t) {
    std::string name = to_string(t); // "combined image sampler": the enumerator with spaces
    std::replace(name.begin(), name.end(), ' ', '_');
    return "kdop::DescriptorType::" + name;
}

std::string words_initializer(const std::vector<std::uint32_t>& words) {
    std::string out;
    for (std::size_t i = 0; i < words.size(); ++i)
        out += fmt::format("{}0x{:08x},{}", i % 8 ? " " : "    ", words[i],
                           i % 8 == 7 || i + 1 == words.size() ? "\n" : "");
    return out;
}

// Emits `text` as a named array once per distinct content and returns the name to refer to it.
class DedupArrays {
public:
    DedupArrays(std::string prefix) : prefix_(std::move(prefix)) {}
    std::string name_for(const std::string& declaration_type, const std::string& body, std::string& out) {
        auto [it, inserted] = names_.try_emplace(body, fmt::format("{}_{}", prefix_, names_.size()));
        if (inserted) out += fmt::format("const {} {}[] = {{\n{}}};\n\n", declaration_type, it->second, body);
        return it->second;
    }

private:
    std::string prefix_;
    std::map<std::string, std::string> names_;
};

// A float as a C++ literal that reads back as the same float: "1.0f", "0.1f", "1e-05f".
std::string float_literal(float value) {
    std::string text = fmt::format("{}", value);
    if (text.find_first_of(".e") == std::string::npos) text += ".0";
    return text + "f";
}

// The members of an upscaling resolve's settings (upscale-filter:, upscale-sample-distance:,
// upscale-box-scale:); none for one that did not upscale, whose members keep their defaults.
std::string upscale_declaration(const ResolveSettings& r) {
    if (!r.upscaling) return {};
    const char* kind = r.sample_distance.kind == SampleDistance::Kind::ue4     ? "ue4"
                       : r.sample_distance.kind == SampleDistance::Kind::fixed ? "fixed"
                                                                               : "all";
    return fmt::format("    true, // upscaling\n"
                       "    kdop::UpscaleFilter::{}, // upscale-filter\n"
                       "    {{kdop::SampleDistance::Kind::{}, {}}}, // upscale-sample-distance: {}\n"
                       "    kdop::BoxScale::{}, // upscale-box-scale\n",
                       to_string(r.upscale_filter), kind, float_literal(r.sample_distance.pixels),
                       to_string(r.sample_distance), to_string(r.box_scale));
}

// The manifest's resolve, as constants an engine reads at compile time.
std::string resolve_declaration(const ResolveSettings& r) {
    const char* map = r.color_map == ColorMapKind::power ? "power"
                      : r.color_map == ColorMapKind::log ? "log"
                                                         : "linear";
    std::string exponent = fmt::format("{}", r.color_map_exponent);
    if (exponent.find_first_of(".e") == std::string::npos) exponent += ".0";
    return fmt::format("// The TAA resolve the manifest records these variants were measured with (its gamma:,\n"
                       "// current-weight:, color-map:, history-filter: and dilate-motion: lines, and its upscale-\n"
                       "// lines where it upscaled): build the resolve with it, and give a varclip variant `gamma`\n"
                       "// as its push constant.\n"
                       "inline constexpr kdop::ResolveSettings resolve_settings{{\n"
                       "    {}, // gamma\n"
                       "    {}, // current_weight\n"
                       "    kdop::ColorMapKind::{}, {}, // color-map: {}\n"
                       "    kdop::HistoryFilter::{}, // history-filter: {}\n"
                       "    {}, // dilate_motion\n"
                       "{}"
                       "}};\n\n",
                       float_literal(r.gamma), float_literal(r.current_weight), map, exponent, color_map_text(r),
                       r.history_filter == HistoryFilter::catmull_rom ? "catmull_rom" : "bilinear",
                       to_string(r.history_filter), r.dilate_motion ? "true" : "false", upscale_declaration(r));
}

} // namespace

const std::set<std::string_view>& cpp_keywords() {
    // C++23's keywords and alternative tokens ([lex.key], [lex.digraph]); cmake/KdopVariants.cmake
    // refuses the same list at configure time, and a test keeps the two equal.
    static const std::set<std::string_view> keywords = {
        "alignas",     "alignof",   "and",        "and_eq",    "asm",      "auto",         "bitand",
        "bitor",       "bool",      "break",      "case",      "catch",    "char",         "char8_t",
        "char16_t",    "char32_t",  "class",      "compl",     "concept",  "const",        "consteval",
        "constexpr",   "constinit", "const_cast", "continue",  "co_await", "co_return",    "co_yield",
        "decltype",    "default",   "delete",     "do",        "double",   "dynamic_cast", "else",
        "enum",        "explicit",  "export",     "extern",    "false",    "float",        "for",
        "friend",      "goto",      "if",         "inline",    "int",      "long",         "mutable",
        "namespace",   "new",       "noexcept",   "not",       "not_eq",   "nullptr",      "operator",
        "or",          "or_eq",     "private",    "protected", "public",   "register",     "reinterpret_cast",
        "requires",    "return",    "short",      "signed",    "sizeof",   "static",       "static_assert",
        "static_cast", "struct",    "switch",     "template",  "this",     "thread_local", "throw",
        "true",        "try",       "typedef",    "typeid",    "typename", "union",        "unsigned",
        "using",       "virtual",   "void",       "volatile",  "wchar_t",  "while",        "xor",
        "xor_eq"};
    return keywords;
}

std::optional<std::string> cpp_namespace_problem(std::string_view ns) {
    static const std::regex pattern(R"([A-Za-z_][A-Za-z0-9_]*(::[A-Za-z_][A-Za-z0-9_]*)*)");
    if (!std::regex_match(ns.begin(), ns.end(), pattern)) return "is not a C++ namespace (identifiers separated by ::)";
    for (std::size_t start = 0; start <= ns.size();) {
        const std::size_t end = std::min(ns.find("::", start), ns.size());
        const std::string_view part = ns.substr(start, end - start);
        if (cpp_keywords().count(part))
            return fmt::format("holds the C++ keyword '{}', which cannot name a namespace", part);
        // [lex.name]: names with a double underscore or an underscore and a capital are the
        // implementation's.
        if (part.find("__") != std::string_view::npos || (part.size() > 1 && part[0] == '_' && std::isupper(part[1])))
            return fmt::format("holds '{}', a name reserved for the C++ implementation", part);
        start = end + 2;
    }
    return std::nullopt;
}

std::optional<std::string> registry_files_problem(const std::filesystem::path& header,
                                                  const std::filesystem::path& source,
                                                  const std::filesystem::path& depfile,
                                                  const std::filesystem::path& json) {
    const std::pair<const char*, const std::filesystem::path*> files[] = {
        {"--header", &header}, {"--source", &source}, {"--depfile", &depfile}, {"--json", &json}};
    for (auto [option, path] : files) {
        if (path->empty()) continue;
        if (auto ok = check_output_file(*path, option); !ok) return ok.error().message;
    }
    for (std::size_t i = 0; i < std::size(files); ++i)
        for (std::size_t j = i + 1; j < std::size(files); ++j) {
            const std::filesystem::path &a = *files[i].second, &b = *files[j].second;
            if (a.empty() || b.empty()) continue;
            if (a.lexically_normal() == b.lexically_normal() || same_file(a, b))
                return fmt::format("{} and {} both name {}; the registry's header, source, depfile and JSON are "
                                   "separate files",
                                   files[i].first, files[j].first, shown_text(a.string()));
        }
    const std::string name = header.filename().string();
    for (char ch : name) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (ch == '"' || ch == '\\' || c < 0x20 || c == 0x7f)
            return fmt::format("--header {}: the source includes the header as #include \"{}\", which cannot hold "
                               "a quote, a backslash or a control byte; rename it",
                               shown_text(header.string()), shown_text(name));
    }
    return std::nullopt;
}

RegistrySources write_registry(std::span<const BuiltVariant> variants, std::string_view cpp_namespace,
                               std::string_view header_include, const std::optional<ResolveSettings>& resolve) {
    // Distinct sets, modes and neighborhoods in first-seen order, for the summary line.
    std::vector<std::string> sets, modes, neighborhoods;
    auto note = [](std::vector<std::string>& list, std::string value) {
        if (std::find(list.begin(), list.end(), value) == list.end()) list.push_back(std::move(value));
    };
    std::vector<std::string> shaders;
    for (const BuiltVariant& v : variants) {
        if (v.spec.mode == Mode::shader) {
            shaders.push_back(v.name);
            continue;
        }
        if (!v.spec.set.name.empty()) note(sets, v.spec.set.name);
        note(modes, to_string(v.spec.mode));
        note(neighborhoods, to_string(v.spec.neighborhood));
    }
    const std::size_t clips = variants.size() - shaders.size();
    std::string summary =
        fmt::format("{} k-DOP clipping variant{}: sets {}; modes {}; neighborhoods {}", clips, clips == 1 ? "" : "s",
                    fmt::join(sets, ", "), fmt::join(modes, ", "), fmt::join(neighborhoods, ", "));
    if (!shaders.empty()) summary += fmt::format("; the project's shaders {}", fmt::join(shaders, ", "));
    const std::string banner =
        fmt::format("// Generated by kdop-gen {} (generator/registry_writer.cpp). Do not edit;\n"
                    "// kdop_add_variants() regenerates it when an axis set, template or the generator changes.\n",
                    KDOP_VERSION);

    RegistrySources out;
    out.header = banner;
    out.header += fmt::format("// {}\n#pragma once\n\n#include <kdop/variant.h>\n\nnamespace {} {{\n\n",
                              line_comment_text(summary), cpp_namespace);
    out.header += "// The variants embedded in this target, in generation order (sets x modes x neighborhoods).\n";
    out.header += "// Look one up with variants().find(\"dop32-clip-n9\").\n";
    out.header += "kdop::VariantList variants();\n\n";
    if (resolve) out.header += resolve_declaration(*resolve);
    out.header += fmt::format("}} // namespace {}\n", cpp_namespace);

    std::string arrays;
    DedupArrays modules("spirv"), bindings("bindings"), push_constants("push_constants");
    std::string table;
    std::size_t distinct_modules = 0;
    std::set<std::uint64_t> hashes;
    for (const BuiltVariant& v : variants) {
        std::uint64_t hash = spirv_hash(v.spirv);
        distinct_modules += hashes.insert(hash).second;
        std::string module = modules.name_for("std::uint32_t", words_initializer(v.spirv), arrays);

        std::string binding_body;
        for (const BindingInfo& b : v.interface.bindings)
            binding_body += fmt::format("    {{{}, {}, {}, {}, {}, 0x{:x}, {}, {}}},\n", b.set, b.binding,
                                        cpp_enum(b.type), cpp_string_literal(b.name), b.count,
                                        vulkan_stage_bit(v.interface.stage), b.block_size, b.format);
        std::string binding_array =
            binding_body.empty() ? "nullptr" : bindings.name_for("kdop::DescriptorBinding", binding_body, arrays);

        std::string push_body;
        for (const PushConstantInfo& p : v.interface.push_constants)
            push_body += fmt::format("    {{{}, {}, {}}},\n", cpp_string_literal(p.name), p.offset, p.size);
        std::string push_array =
            push_body.empty() ? "nullptr" : push_constants.name_for("kdop::PushConstantMember", push_body, arrays);

        const auto& ls = v.interface.local_size;
        table += fmt::format(
            "    {{{}, {}, kdop::Mode::{}, kdop::Neighborhood::{}, kdop::Form::{}, kdop::Numerics::{}, {},\n"
            "     {}, {}, 0x{:016x}ull,\n"
            "     {}, {{{}, {}, {}}}, {}, {}, {}, {}, {}, kdop::ShaderStage::{}, {}}},\n",
            cpp_string_literal(v.name), cpp_string_literal(v.spec.set.name), to_string(v.spec.mode),
            to_string(v.spec.neighborhood), to_string(v.spec.form), to_string(v.spec.numerics), v.spec.set.axes.size(),
            module, v.spirv.size(), hash, cpp_string_literal(v.interface.entry_point), ls[0], ls[1], ls[2],
            binding_array, v.interface.bindings.size(), push_array, v.interface.push_constants.size(),
            v.interface.push_constant_size, to_string(v.interface.stage), v.interface.color_output_count);
    }

    out.source = banner;
    out.source +=
        fmt::format("// {}\n// {} distinct SPIR-V module{}; variants with identical modules share one array.\n\n",
                    line_comment_text(summary), distinct_modules, distinct_modules == 1 ? "" : "s");
    out.source +=
        fmt::format("#include \"{}\"\n\n#include <cstdint>\n#include <iterator>\n\nnamespace {} {{\nnamespace {{\n\n",
                    header_include, cpp_namespace);
    out.source += arrays;
    out.source += "const kdop::Variant kVariants[] = {\n" + table + "};\n\n} // namespace\n\n";
    out.source += "kdop::VariantList variants() { return {kVariants, std::size(kVariants)}; }\n\n";
    out.source += fmt::format("}} // namespace {}\n", cpp_namespace);
    return out;
}

} // namespace kdop
