// The files a built variant is written as: its GLSL, its HLSL and its SPIR-V, ready for
// write_files_atomically (core/write_files.h).
#pragma once

#include "core/result.h"
#include "core/write_files.h"
#include "generator/variant_builder.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace kdop {

// <dir>/<name>.glsl, .hlsl and .wgsl (the includable function in each of kShaderLanguages) and
// <dir>/<name>.comp (compute shader).
std::vector<OutputFile> glsl_files(const BuiltVariant& v, const std::filesystem::path& dir);
// <dir>/<name>.glsl, .hlsl and .wgsl: the includable function alone, for a project's own shaders.
std::vector<OutputFile> function_files(const BuiltVariant& v, const std::filesystem::path& dir);
// A module's words as the little-endian bytes of a .spv file.
std::string spirv_bytes(std::span<const std::uint32_t> words);
// <dir>/<name>.spv: the optimized module's bytes.
OutputFile spirv_file(const BuiltVariant& v, const std::filesystem::path& dir);

struct GeneratedVariants {
    std::vector<BuiltVariant> built; // in the order of the specs
    std::size_t files = 0;           // written
};

// `kdop gen`: builds `specs` (build_variants, on `threads`) and writes each one's glsl_files and
// spirv_file into `dir`, and their reflection as variants.json (generator/reflection_json.h, with
// `resolve`, a manifest's recorded resolve), all or nothing.
Result<GeneratedVariants> generate_variants(std::span<const VariantSpec> specs, const std::filesystem::path& dir,
                                            unsigned threads, const BuildProgress& progress = {},
                                            const std::optional<ResolveSettings>& resolve = std::nullopt);

} // namespace kdop
