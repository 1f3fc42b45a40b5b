// The C++ registry of a set of built variants: a header declaring `<namespace>::variants()` and a
// source holding every variant's SPIR-V words and interface (see include/kdop/variant.h).
// Variants whose SPIR-V is identical share one array.
#pragma once

#include "variant_builder.h"

#include <span>
#include <string>
#include <string_view>

namespace kdop {

struct RegistrySources {
    std::string header;
    std::string source;
};

// `cpp_namespace` must satisfy is_valid_cpp_namespace; `header_include` is what the source
// #includes to reach the header (its file name, when both sit in one directory).
RegistrySources write_registry(std::span<const BuiltVariant> variants, std::string_view cpp_namespace,
                               std::string_view header_include);

// Identifiers separated by "::", e.g. "my_app::taa".
bool is_valid_cpp_namespace(std::string_view ns);

} // namespace kdop
