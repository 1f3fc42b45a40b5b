// The built-in axis sets: every shader_templates/axis_sets/*.axes, compiled in (embedded_files.h),
// named by its file stem. This is the one list of them: the CLI's help, `kdop list`, kdop-gen and
// kdop_add_variants() (which globs the same folder) all follow it. Adding a set is adding a file.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace kdop {

// The RGB box, the baseline every other set is compared with (time and accuracy relative to it,
// "looser than the RGB AABB"), and the set whose interface stands in for a variant's in the probe.
inline constexpr const char* kRgbBox = "aabb";

// Ordered by axis count, then by name: the boxes first, the 32-DOP last. That order is the order
// of `kdop list`, of every default selection and of every report.
std::span<const std::string> builtin_set_names();

// "aabb, ycocg, ...": for help texts and error messages.
std::string builtin_set_list();

bool is_builtin_set(std::string_view name);

// The embedded path ("shader_templates/axis_sets/dop22.axes", what errors cite) and the text of a
// built-in set; nullopt for other names.
std::string builtin_set_path(std::string_view name);
std::optional<std::string_view> builtin_set_text(std::string_view name);

} // namespace kdop
