// The content of `kdop taa`: a scene is a background image under two moving objects (a red box and
// a dark ellipse, drawn by shader_templates/taa_frame.comp.in); this file says where they are on
// each frame and where the camera's sample falls in each pixel.
//
// Animation: each object swings on a sine path, so it never jumps (a jump would be a disocclusion
// no motion vector describes) and the measured frames see it at every speed from rest to about
// 1.2% (the red box) and 1.9% (the dark ellipse) of the frame's width per frame. Jitter: the R2 sequence (Roberts
// 2018), 10 entries, as in Ikkala et al. 2024, centered on the pixel.
#pragma once

#include "image.h"
#include "image_io.h"
#include "result.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace kdop {

struct TaaScene {
    std::string name; // "grass", "asphalt", a real texture's name or a background file's stem
    Image background; // linear RGB, frame-sized; repeated and minified by the shader
};

// The paper's two backgrounds as kdop's synthetic families ("grass": high-frequency chroma and
// luma; "asphalt": high-frequency luma), then the first installed real texture, if any.
std::vector<TaaScene> default_taa_scenes(std::uint32_t width, std::uint32_t height, std::uint64_t seed);

// A user's background: read, then tiled or cropped to the frame. The error names the file; values
// must lie in [0, 1] (the metric is LDR-FLIP), and one that does not is named with its pixel.
Result<TaaScene> read_taa_scene(const std::string& path, std::uint32_t width, std::uint32_t height,
                                InputSpace space = InputSpace::from_file);

struct FrameState {
    glm::vec2 jitter{0};                    // sample offset from the pixel center, pixels
    glm::vec2 car_center{0}, car_motion{0}; // pixels; motion since the previous frame
    glm::vec2 shadow_center{0}, shadow_motion{0};
};

// Frame `frame` of a sequence of frames `width` x `height`. Without `animate` the objects stay
// where they are on frame 0 and do not move; without `jitter` every sample is at the pixel center.
FrameState frame_state(std::uint32_t frame, std::uint32_t width, std::uint32_t height, bool animate, bool jitter);

// Entry `index` (mod 10) of the R2 jitter, in (-0.5, 0.5) pixels.
glm::vec2 r2_jitter(std::uint32_t index);

} // namespace kdop
