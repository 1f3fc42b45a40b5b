// Axis sets: the directions of one k-DOP (k = 2 x axis count), parsed and validated from the
// plain-text format of shader_templates/axis_sets/*.axes:
//
//   # comment (anywhere; '#' to end of line)
//   name: dop22                      lowercase letters, digits and single '-' between them
//   provenance: where the numbers come from
//   color_map: log                   optional: the space the set was fitted in (color_map.h)
//   vec3(1, 0, 0),                   one axis per line: three numbers separated by spaces or
//   0.5, 0, -0.5                     commas, optionally wrapped in vec3(...) and followed by ','
//
// Validation refuses, with "file:line: reason": numbers that do not parse, lines with other than
// three numbers, NaN/infinite or zero-length axes, an axis parallel or antiparallel to an earlier
// one (both give the same slab), and sets whose axes do not span 3-D (the k-DOP would be unbounded).
#pragma once

#include "core/color_map.h"
#include "core/result.h"
#include "core/variant_key.h" // is_valid_set_name

#include <glm/vec3.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

struct Axis {
    glm::dvec3 direction; // exactly as written in the file, not normalized
    int line;             // 1-based line in the file, for messages and generated comments
};

struct AxisSet {
    std::string name;       // set name used in variant names, e.g. "dop16-grass"
    std::string provenance; // where the numbers come from
    std::string origin;     // file the set was read from, as shown in messages and generated code
    // The space the set was fitted in (kdop optimize --color-map), where its file says; a clip in
    // another space is not the one it was fitted for. The built-in sets say nothing.
    std::optional<ColorMap> color_map;
    std::vector<Axis> axes;
};

// Two axes closer than this angle (radians) are refused as duplicates: the published sets are
// printed to 6 decimals, so axes meant to be equal can differ by about 1e-6 in direction.
inline constexpr double kParallelAxisAngle = 1e-5;

// `direction` at unit length, for any finite nonzero direction: scaled by its largest component
// first, so that 1e200 does not overflow and 1e-200 does not underflow on the way.
glm::dvec3 unit_direction(const glm::dvec3& direction);

// Parses and validates the text of an axis-set file; `origin` names it in error messages.
Result<AxisSet> parse_axis_set(std::string_view text, std::string_view origin);

// Where `set` was fitted in another space than the one `used` by a clip (`clipping`, e.g.
// "this run (--color-map)"), the warning to print; nothing where it was, or where the set does
// not say (the built-in sets).
std::optional<std::string> fitted_space_mismatch(const AxisSet& set, const ColorMap& used, std::string_view clipping);

} // namespace kdop
