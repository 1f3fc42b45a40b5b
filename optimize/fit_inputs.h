// What kdop optimize fits to: images and frame sequences together, as frames read one at a time
// (fit/frame_neighborhoods.h), and the pixels its distance to the ideal clip is measured on.
#pragma once

#include "core/color_map.h"
#include "core/result.h"
#include "fit/axis_fit.h"
#include "harness/progress.h"
#include "images/image_io.h"
#include "sequence/sequence.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace kdop {

// Frames of each sequence held out of a fit, to judge it on (kdop choose --holdout): with `block`
// above 0, of the frames after `warmup`, every other block of `block` frames, the second, the
// fourth and so on; none with 0. The warm-up frames are fitted to (no figure is measured on them).
struct Holdout {
    std::size_t block = 0, warmup = 0;
    bool held_out(std::size_t index) const { return block > 0 && index >= warmup && (index - warmup) / block % 2 == 1; }
};

struct FitInputOptions {
    std::vector<std::string> images, sequences; // files; sequence folders
    std::size_t frame_step = 1;                 // every frame_step-th frame of each sequence, from the first
    Holdout holdout;                            // frames left out of the fit
    InputSpace input_space = InputSpace::from_file;
    ColorMap color_map; // the fit's space: every color is mapped on reading
};

struct FitInputs {
    std::vector<FitFrame> frames;                           // the images, then each sequence's frames
    std::vector<std::shared_ptr<const Sequence>> sequences; // as read, frames not yet stepped; frames share them
    std::vector<std::filesystem::path> paths;               // every file read, for outputs to keep clear of
    std::string description;                                // "desert5.png, intro (48 of 96 frames)"
};

// Reads the sequences' manifests and the images' headers (no pixel yet). Refuses an image or
// sequence given twice and frames smaller than 3x3; a frame's pixels are checked when it is read.
Result<FitInputs> fit_inputs(const FitInputOptions& options);

// The distance's pixels: `per_input` seeded pixels of each image under each of its ghosting
// histories (kdop accuracy's measure), and of each sequence as many, spread over its frames.
Result<std::vector<ClipSample>> fit_distance_samples(const FitInputOptions& options, const FitInputs& inputs,
                                                     Neighborhood shape, std::size_t per_input, std::uint64_t seed);

} // namespace kdop
