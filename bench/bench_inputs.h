// The content every bench measurement runs on, so the static, timed and callgrind figures describe
// the same work: the grass texture as the current frame and asphalt as the history, so every pixel
// is clipped (the costlier path where a variant branches). Seeded; the seeds go into the report.
#pragma once

#include "images/image.h"
#include "images/texture_cases.h"

#include <cstdint>
#include <utility>

namespace kdop::bench {

inline constexpr std::uint64_t kCurrentSeed = 1, kHistorySeed = 2;

inline std::pair<Image, Image> bench_inputs(std::uint32_t width, std::uint32_t height) {
    return {make_texture(TextureFamily::grass, width, height, kCurrentSeed),
            make_texture(TextureFamily::asphalt, width, height, kHistorySeed)};
}

} // namespace kdop::bench
