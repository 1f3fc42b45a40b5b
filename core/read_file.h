// Reading a whole file as bytes: the one way kdop reads axis files, manifests, shaders and CSV.
// Only regular files are read: a device such as /dev/zero, a pipe or a folder is refused before
// anything is read, so an input can neither hang kdop nor fill its memory. Every file read is
// noted as an input of the run (core/input_files.h), so no output can replace it.
#pragma once

#include "core/result.h"

#include <filesystem>
#include <optional>
#include <string>

namespace kdop {

// The file's bytes, or an error "<path>: <reason>" (missing, a folder, not a regular file,
// unreadable).
Result<std::string> read_input_file(const std::filesystem::path& path);

// The same for a file of kdop's own that this run will replace (an output folder's listing): read
// the same way, but not noted as an input.
Result<std::string> read_own_file(const std::filesystem::path& path);

// read_input_file where the caller words the error itself.
std::optional<std::string> read_file(const std::filesystem::path& path);

// Why `path` cannot be read as an input file ("does not exist", "is a directory", ...), or
// nothing when it is a regular file. For readers that open files through a library (images).
std::optional<std::string> not_a_readable_file(const std::filesystem::path& path);

} // namespace kdop
