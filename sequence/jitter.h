// The camera's sub-pixel jitter every content source kdop makes uses: the R2 sequence (Roberts
// 2018), as Ikkala et al. 2024 use it, centered on the pixel; for content rendered to be upscaled,
// the Halton (2, 3) sequence over as many phases as FSR 2 and XeSS ask for at the ratio.
#pragma once

#include <glm/vec2.hpp>

#include <cstdint>

namespace kdop {

// Entry `index` of the R2 sequence, in (-0.5, 0.5) pixels. The TAA sequences cycle through the
// first 10 (r2_jitter(frame % 10)); a supersampled reference takes the first N.
glm::vec2 r2_point(std::uint32_t index);

// Entry `index` (mod 10) of the R2 jitter.
inline glm::vec2 r2_jitter(std::uint32_t index) { return r2_point(index % 10); }

// The phases of an upscaling jitter at `ratio` (output over input size per axis): ceil(8 ratio^2),
// FSR 2's count, so that every output pixel sees about eight samples per cycle.
std::uint32_t upscale_jitter_phases(double ratio);
// Entry `index` (mod `phases`) of the Halton (2, 3) sequence, from its second point (the first is
// 0, 0), centered: in (-0.5, 0.5) input pixels.
glm::vec2 halton_jitter(std::uint32_t index, std::uint32_t phases);

} // namespace kdop
