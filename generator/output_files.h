// Writing generated files all-or-nothing: every file is first written next to its destination
// under a temporary name, and only when all of them are complete are they renamed into place.
// A failure removes the temporaries, so a failed run leaves no partial output behind.
#pragma once

#include "result.h"
#include "variant_builder.h"

#include <filesystem>
#include <string>
#include <vector>

namespace kdop {

struct OutputFile {
    std::filesystem::path path;
    std::string content; // bytes, written as is
};

Result<void> write_files_atomically(const std::vector<OutputFile>& files);

// <dir>/<name>.glsl (includable function) and <dir>/<name>.comp (compute shader).
std::vector<OutputFile> glsl_files(const BuiltVariant& v, const std::filesystem::path& dir);
// <dir>/<name>.spv: the optimized module's words as little-endian bytes.
OutputFile spirv_file(const BuiltVariant& v, const std::filesystem::path& dir);

} // namespace kdop
