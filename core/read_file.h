// Reading a whole file as bytes: the one way kdop reads axis files, manifests, shaders and CSV.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace kdop {

// The file's bytes; nullopt when it is not a regular file or cannot be read to the end.
std::optional<std::string> read_file(const std::filesystem::path& path);

} // namespace kdop
