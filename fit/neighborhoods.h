// A scene's neighborhoods as a fit sees them: every pixel's 3x3 (or plus-shaped) set of colors, as
// points, with repeats counted instead of stored.
#pragma once

#include "images/image.h"

#include <kdop/variant.h>

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace kdop {

// Neighborhoods of images (clamp to edge, as the shaders read them), as points. A neighborhood
// that repeats one before it exactly (flat areas, repeated texels: on the colobot grass texture,
// 46% of them) is kept once with how many times it appears, so the objective computes its k-DOP
// once and weighs it by that count.
struct Neighborhoods {
    std::size_t size = 9;               // points per neighborhood: 9 (n9) or 5 (n5)
    std::vector<glm::dvec3> points;     // distinct() x size, in order of first appearance
    std::vector<std::uint32_t> repeats; // how many times each distinct neighborhood appears
    std::size_t total = 0;              // neighborhoods, repeats included
    std::size_t count() const { return total; }
    std::size_t distinct() const { return repeats.size(); }
    std::span<const glm::dvec3> at(std::size_t i) const { return {points.data() + i * size, size}; }
};

// Every neighborhood of the images.
Neighborhoods gather_neighborhoods(std::span<const Image> images, Neighborhood shape);
// The same into `out`, reusing its storage: for a frame gathered again and again.
void gather_neighborhoods(std::span<const Image> images, Neighborhood shape, Neighborhoods& out);

// `count` neighborhoods of a scene's frames (all of them where there are fewer), seeded and
// stratified: each frame gives its share by pixel count, and within a frame the pixels, ordered by
// luminance, are cut into that many strata of equal size, one pixel drawn from each. So dark and
// bright areas are sampled as often as they occur, and the same seed draws the same pixels. Frames
// are added one at a time, in any order and by any process (each frame draws with its own
// generator); finish() counts repeats in frame order.
class NeighborhoodSampler {
public:
    NeighborhoodSampler(Neighborhood shape, std::span<const std::uint64_t> frame_pixels, std::size_t count,
                        std::uint64_t seed);
    std::size_t share(std::size_t frame) const { return share_[frame]; }
    // Draws frame `frame`'s share from its image.
    void add(std::size_t frame, const Image& image);
    // Frame `frame`'s drawn points (its share, at most its pixels, x the neighborhood's size), for
    // a process to hand to the others, and how many it draws whoever reads it.
    std::vector<glm::dvec3>& drawn(std::size_t frame) { return drawn_[frame]; }
    std::size_t drawn_points(std::size_t frame) const;
    Neighborhoods finish();

private:
    Neighborhood shape_;
    std::uint64_t seed_;
    std::vector<std::size_t> share_;
    std::vector<std::uint64_t> pixels_;
    std::vector<std::vector<glm::dvec3>> drawn_;
};

// The sampler on images held together.
Neighborhoods sample_neighborhoods(std::span<const Image> images, Neighborhood shape, std::size_t count,
                                   std::uint64_t seed);

} // namespace kdop
