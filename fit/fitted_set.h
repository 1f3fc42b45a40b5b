// A fitted axis set as an axis-set file every kdop command reads (docs/embedding.md, "Axis-set files"): a
// comment block saying how it was made, `name:`, `provenance:`, one axis per line. Written only
// from what is deterministic (no timings), so the same fit gives the same bytes.
#pragma once

#include "core/color_map.h"
#include "core/result.h"
#include "generator/axis_set.h"

#include <glm/vec3.hpp>

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace kdop {

struct FittedSetText {
    std::string name;                  // a valid set name
    std::string provenance;            // one line
    std::vector<std::string> comments; // lines of the comment block, without '#'
    std::optional<ColorMap> color_map; // the space it was fitted in, written as `color_map:` when given
};

// The file's text, checked by parsing it back: an axis the parser would refuse (two fitted axes
// within 1e-5 rad of each other) is an error here, not a file that fails later.
Result<std::string> fitted_set_file(const FittedSetText& text, std::span<const glm::dvec3> axes);

} // namespace kdop
