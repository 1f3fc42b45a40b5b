// One picture per scene for `kdop taa`: the same frame of the ghosting sequence from every variant,
// side by side in a grid, each under its label, the aliased frame first, so a reader sees at a
// glance which clip leaves a trail behind the moving objects and how long it is.
#pragma once

#include "core/result.h"
#include "images/image.h"
#include "scenes/taa_scene.h"

#include <span>
#include <string>

namespace kdop {

struct LabeledFrame {
    std::string label;
    const Image* frame;               // all of one size, values in [0, 1]
    const Image* error_map = nullptr; // shown under the frame where given: its FLIP map, in magma
    std::string note = {};            // a line under it: the figures of this variant
};

// The scale of the error maps, drawn under the grid: `bar` (one row, its left end for 0, its right
// for 1) stretched to a strip, "0" and "1" at its ends and the caption beside it.
struct ColorScale {
    const Image* bar;
    std::string caption;
};

// A grid `columns` crops wide (each frame over its error map, if any), each with a strip above it
// holding its label and, where given, one under it holding its note (white on black, DejaVu Sans
// from fonts-dejavu-core, or OpenImageIO's own font where that is missing; a label too long for its
// crop is drawn smaller), and the color scale under the grid where given. Errors when the crop
// leaves a frame or the text cannot be drawn.
Result<Image> trail_picture(std::span<const LabeledFrame> frames, const TrailCrop& crop, std::uint32_t columns = 4,
                            const ColorScale* scale = nullptr);

// The part of a width x height frame `crop` shows, not magnified: all a picture needs of the frame
// (a 320x180 crop of a 1080p frame is 2.8% of it). An error where the crop leaves the frame. The
// crop of the parts is {0, 0, crop.width, crop.height, crop.scale}.
Result<Image> crop_of(const Image& frame, const TrailCrop& crop);
Result<std::vector<float>> crop_of(std::span<const float> map, std::uint32_t width, std::uint32_t height,
                                   const TrailCrop& crop);

} // namespace kdop
