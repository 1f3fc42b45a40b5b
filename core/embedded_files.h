// Files compiled into the generator (the built-in axis sets and the shader templates under
// shader_templates/), so `kdop` and `kdop-gen` work without the source tree. The list is produced
// at build time by cmake/embed_files.cmake; editing one of the files rebuilds the generator,
// which in turn regenerates every variant built from it.
#pragma once

#include <optional>
#include <span>
#include <string_view>

namespace kdop {

struct EmbeddedFile {
    std::string_view path; // relative to the repository root, e.g. "shader_templates/axis_sets/dop22.axes"
    std::string_view text;
};

std::span<const EmbeddedFile> embedded_files();

std::optional<std::string_view> find_embedded_file(std::string_view path);

} // namespace kdop
