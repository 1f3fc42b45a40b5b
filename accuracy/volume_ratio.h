// k-DOP volume over hull volume: how much more a variant's polytope accepts than the convex hull,
// on a seeded sample of pixels (Qhull is too slow to take every pixel of every variant: a 32-DOP's
// slab intersection costs about 0.3 ms).
#pragma once

#include "core/result.h"
#include "generator/axis_set.h"
#include "generator/variant_spec.h"
#include "images/image.h"

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace kdop {

// A hull whose volume is below this share of its bounding cube (the largest side cubed) counts as
// flat: its ratio would measure the slab padding, not the axes.
inline constexpr double kSolidHull = 1e-6;

struct SolidPixel {
    std::uint32_t x, y;
    double hull_volume;
};

// Up to `count` pixels whose neighborhood hull is solid, taken in a random order fixed by `seed`
// (fewer where the image has fewer).
Result<std::vector<SolidPixel>> sample_solid_pixels(const Image& current, Neighborhood shape, std::size_t count,
                                                    std::uint64_t seed);

struct VolumeRatio {
    double median = NAN, mean = NAN;
    std::size_t pixels = 0;
};

// The padded k-DOP of the variant (as the CPU reference builds it) over the hull, at each sampled pixel.
Result<VolumeRatio> volume_ratio(const Image& current, std::span<const SolidPixel> sample, const AxisSet& set,
                                 Mode mode, Neighborhood shape, double gamma);

} // namespace kdop
