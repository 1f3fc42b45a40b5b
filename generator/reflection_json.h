// The registry as JSON, for engines and build systems that cannot read the C++ one: a runtime in
// Rust (wgpu), C# or Zig, a Meson, Bazel or premake build. Every variant and project shader with
// what its pipeline needs (stage, entry point, local size, bindings, push constants, color outputs),
// its SPIR-V's size and hash (the registry's FNV-1a 64) and file where one was written, and, for a
// variant, its axis set and where the set's numbers came from, and the TAA resolve a manifest
// records its variants were measured with. Written beside the header by
// kdop_add_variants, by `kdop-gen registry --json` and by `kdop gen` (variants.json); the format is
// versioned and described by docs/reflection.schema.json, which the tests validate it against.
#pragma once

#include "generator/variant_builder.h"

#include <functional>
#include <optional>
#include <span>
#include <string>

namespace kdop {

// The version of the format; a change a reader must know of raises it.
inline constexpr int kReflectionFormatVersion = 1;

// The JSON text (two-space indents, keys in a fixed order, a final line break: the same variants
// give the same bytes). `spirv_file`, where given, names each entry's .spv as the JSON names it
// (relative to the JSON's folder), or nothing where no .spv was written. `resolve`: the resolve a
// manifest records (manifest.h), as "resolve"; null where there is none.
std::string reflection_json(std::span<const BuiltVariant> entries,
                            const std::function<std::optional<std::string>(const BuiltVariant&)>& spirv_file = {},
                            const std::optional<ResolveSettings>& resolve = std::nullopt);

} // namespace kdop
