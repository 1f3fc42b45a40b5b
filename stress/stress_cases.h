// The stress suite's inputs: one image pair per case, made of 3x3 tiles. A tile's nine colors are
// one designed neighborhood (the tile's center pixel sees exactly it) and all nine pixels share the
// tile's history color. Every pixel is checked, so the edge pixels, whose neighborhoods straddle
// two tiles, add mixed neighborhoods of the same magnitudes.
#pragma once

#include "generator/axis_set.h"
#include "images/image.h"
#include "runtime/rectify_pass.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kdop {

struct StressCase {
    std::string name;        // short, a column of the table: "hdr-6e4"
    std::string description; // what it holds
    TextureFormat format = TextureFormat::rgba32f;
    Image current, history; // as the shader reads them: rgba16f cases are already rounded to half
};

// The cases for variants of `set`, in table order; one of them aims rays exactly parallel to the
// set's own slabs. Random colors come from `seed`, and each case has its own stream, so a case's
// content does not depend on which cases come before it.
std::vector<StressCase> make_stress_cases(const AxisSet& set, std::uint64_t seed);
std::size_t stress_case_count();

} // namespace kdop
