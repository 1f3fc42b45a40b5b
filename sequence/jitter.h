// The camera's sub-pixel jitter every content source kdop makes uses: the R2 sequence (Roberts
// 2018), as Ikkala et al. 2024 use it, centered on the pixel.
#pragma once

#include <glm/vec2.hpp>

#include <cstdint>

namespace kdop {

// Entry `index` of the R2 sequence, in (-0.5, 0.5) pixels. The TAA sequences cycle through the
// first 10 (r2_jitter(frame % 10)); a supersampled reference takes the first N.
glm::vec2 r2_point(std::uint32_t index);

// Entry `index` (mod 10) of the R2 jitter.
inline glm::vec2 r2_jitter(std::uint32_t index) { return r2_point(index % 10); }

} // namespace kdop
