// Where a file named inside a project's text may be read from: a shader's #include, a manifest's
// `set:` line. Each is confined to a folder, so a name such as "/etc/passwd" or "../../secret"
// cannot bring another file into a build, nor its lines into the build's messages.
#pragma once

#include <filesystem>

namespace kdop {

// Whether `file` lies in `folder` or below it, links and ".." resolved (an empty folder is the
// current one).
bool is_inside_folder(const std::filesystem::path& file, const std::filesystem::path& folder);

} // namespace kdop
