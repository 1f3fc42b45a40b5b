// The image pairs `kdop accuracy` measures: a current frame and a history each, grouped in
// families (one chart and one trade table per family).
#pragma once

#include "core/result.h"
#include "images/image.h"
#include "images/image_io.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kdop {

struct AccuracyPair {
    std::string family; // a texture family, a real texture or an input file's stem
    std::string name;   // e.g. "grass/shifted"
    Image current, history;
};

// The ghosting history models measured (texture_cases.h): shifted, moved-object, other-texture.
// `same` is left out: with the history equal to the current frame there is nothing to clip.

// Every synthetic texture family and installed real texture x those models, at width x height.
std::vector<AccuracyPair> builtin_pairs(std::uint32_t width, std::uint32_t height, std::uint64_t seed);

// Each image as a current frame x those models; other-texture takes the image rotated by 180
// degrees (content from elsewhere in the same scene, as on a disocclusion).
Result<std::vector<AccuracyPair>> image_pairs(const std::vector<std::string>& paths,
                                              InputSpace space = InputSpace::from_file);

// `current` x those models, as image_pairs() makes them for one image of `family`.
std::vector<AccuracyPair> ghosting_pairs(const std::string& family, const Image& current);

// One given pair, named after the current frame's file.
Result<AccuracyPair> given_pair(const std::string& current_path, const std::string& history_path,
                                InputSpace space = InputSpace::from_file);

} // namespace kdop
