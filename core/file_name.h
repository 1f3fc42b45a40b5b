// Names from outside kdop that become parts of the files and folders kdop writes: a sequence's
// folder name (its rows, charts, frames and pictures are named after it), a background image's stem
// (its scene's). Checked where they are read, before any work, so that no name can climb out of
// --out (".." or a separator), hide inside a listing or a log (control bytes, bidirectional-text
// controls that show a name reordered), break the JSON and HTML that carry it (invalid UTF-8), or
// fail only at the end of a run (too long once decorated: trade-<name>.kdop-partial-<pid>-<n>.png
// must still fit the file system's 255 bytes).
#pragma once

#include "core/result.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace kdop {

// The longest name kdop makes file names of, in bytes: the longest decoration kdop adds
// (over-time-, -ghosting, a temporary's .kdop-partial-<pid>-<n>) leaves it well inside NAME_MAX.
inline constexpr std::size_t kMaxNameBytes = 128;

// Why `name` cannot name kdop's outputs ("is '..'", "holds a line break (\x0a)", ...), or nothing
// when it can. The caller says whose name it is and what to do.
std::optional<std::string> name_problem(std::string_view name);

} // namespace kdop
