// The C++ registry of a set of built variants: a header declaring `<namespace>::variants()` and a
// source holding every variant's SPIR-V words and interface (see include/kdop/variant.h).
// Variants whose SPIR-V is identical share one array.
#pragma once

#include "generator/variant_builder.h"

#include <filesystem>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>

namespace kdop {

struct RegistrySources {
    std::string header;
    std::string source;
};

// `cpp_namespace` must pass cpp_namespace_problem; `header_include` is what the source
// #includes to reach the header (its file name, when both sit in one directory). `resolve`, a
// manifest's recorded resolve (manifest.h), is declared in the header as
// `inline constexpr kdop::ResolveSettings resolve_settings`, and only where there is one: code that
// needs the settings fails to build against a manifest that lost them instead of guessing.
RegistrySources write_registry(std::span<const BuiltVariant> variants, std::string_view cpp_namespace,
                               std::string_view header_include,
                               const std::optional<ResolveSettings>& resolve = std::nullopt);

// Why `ns` cannot name the registry's namespace, or nullopt where it can: identifiers separated by
// "::", e.g. "my_app::taa", none of them a keyword ("int", "class") or a name reserved for the
// implementation ("__x", "_X").
std::optional<std::string> cpp_namespace_problem(std::string_view ns);
// C++23's keywords and alternative tokens.
const std::set<std::string_view>& cpp_keywords();

// Why the registry's --header, --source, --depfile and --json cannot be written as asked (an empty
// path is not written): a folder or a special file (core/write_files.h check_output_file), two of
// them one file (a HEADER named app.cpp), or a header whose name an #include "..." cannot hold (a
// quote, a backslash, a control byte); nullopt when they can. Checked before any variant is built.
std::optional<std::string> registry_files_problem(const std::filesystem::path& header,
                                                  const std::filesystem::path& source,
                                                  const std::filesystem::path& depfile,
                                                  const std::filesystem::path& json = {});

} // namespace kdop
