// The files a built variant is written as: its GLSL, its HLSL and its SPIR-V, ready for
// write_files_atomically (core/write_files.h).
#pragma once

#include "core/write_files.h"
#include "generator/variant_builder.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace kdop {

// <dir>/<name>.glsl, .hlsl and .wgsl (the includable function in each language) and
// <dir>/<name>.comp (compute shader).
std::vector<OutputFile> glsl_files(const BuiltVariant& v, const std::filesystem::path& dir);
// <dir>/<name>.glsl, .hlsl and .wgsl: the includable function alone, for a project's own shaders.
std::vector<OutputFile> function_files(const BuiltVariant& v, const std::filesystem::path& dir);
// A module's words as the little-endian bytes of a .spv file.
std::string spirv_bytes(std::span<const std::uint32_t> words);
// <dir>/<name>.spv: the optimized module's bytes.
OutputFile spirv_file(const BuiltVariant& v, const std::filesystem::path& dir);

} // namespace kdop
