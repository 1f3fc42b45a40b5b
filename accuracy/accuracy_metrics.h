// How close a variant's clipped colors come to the ideal clip (ideal_clip.h) over one image pair.
//
// Per pixel, with c the current color, h the history, t* the ideal exit and S = max(1, |c|inf) the
// pixel's magnitude (as in kdop's padding):
// - distance: |clipped - (c + t* (h - c))| / S, Euclidean in linear RGB, in units of S so that
//   HDR highlights weigh as they would after tone mapping, not by their raw value (for content
//   within [0, 1], S = 1: plain linear RGB);
// - outside the hull: the history lies more than 1e-4 S beyond the hull along the ray,
//   (1 - t*) |h - c| > 1e-4 S, ten times kdop's slab padding, so a k-DOP that only touches the
//   hull is not counted as accepting what lies outside it;
// - returned unchanged: |clipped - h| <= 1e-5 S.
#pragma once

#include "images/image.h"

#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

namespace kdop {

inline constexpr double kOutsideHull = 1e-4;  // times S, see above
inline constexpr double kUnchanged = 1e-5;    // times S
inline constexpr double kSameDistance = 1e-6; // times S: distances closer than this are a tie

struct ClipAccuracy {
    double mean_dist = NAN, p95_dist = NAN, max_dist = NAN; // p95: nearest rank, ceil(0.95 n)-th smallest
    std::size_t pixels = 0;
    std::size_t outside = 0;          // histories outside the hull
    std::size_t falsely_accepted = 0; // of those, returned unchanged
    double outside_rate() const { return pixels ? double(outside) / double(pixels) : NAN; }
    // The share of histories outside the hull that were returned unchanged; NaN where none was outside.
    double false_accept_rate() const { return outside ? double(falsely_accepted) / double(outside) : NAN; }
};

// S of a pixel, from its current color.
double pixel_magnitude(const glm::vec4& current);

// Each pixel's distance from `clipped` to the ideal clipped color, in units of S (row-major).
std::vector<double> ideal_distances(const Image& current, const Image& history, std::span<const double> ideal_exits,
                                    const Image& clipped);

// The figures of one clipped image; `distances` are its ideal_distances.
ClipAccuracy measure_accuracy(const Image& current, const Image& history, std::span<const double> ideal_exits,
                              const Image& clipped, std::span<const double> distances);

// How often, and by how much, one clip is looser than another on the same pair: distances `a`
// and `b` (from ideal_distances) compared pixel by pixel.
struct Looser {
    double share = NAN;   // of the pixels where a exceeds b by more than kSameDistance
    double largest = NAN; // the largest excess a - b (units of S), 0 if a never exceeds b
};
Looser compare_distances(std::span<const double> a, std::span<const double> b);

} // namespace kdop
