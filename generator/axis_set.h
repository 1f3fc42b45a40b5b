// Axis sets: the directions of one k-DOP (k = 2 x axis count), parsed and validated from the
// plain-text format of shader_templates/axis_sets/*.axes:
//
//   # comment (anywhere; '#' to end of line)
//   name: dop22                      lowercase letters, digits and single '-' between them
//   provenance: where the numbers come from
//   vec3(1, 0, 0),                   one axis per line: three numbers separated by spaces or
//   0.5, 0, -0.5                     commas, optionally wrapped in vec3(...) and followed by ','
//
// Validation refuses, with "file:line: reason": numbers that do not parse, lines with other than
// three numbers, NaN/infinite or zero-length axes, an axis parallel or antiparallel to an earlier
// one (both give the same slab), and sets whose axes do not span 3-D (the k-DOP would be unbounded).
#pragma once

#include "result.h"
#include "variant_key.h" // is_valid_set_name

#include <glm/vec3.hpp>

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

} // namespace kdop
