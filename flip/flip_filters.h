// The separable filters of LDR-FLIP at a given number of pixels per degree (Andersson et al. 2020,
// and NVlabs/flip's separatedConvolutions.pdf for the separation):
//
// - contrast sensitivity (CSF) kernels, one per YCxCz channel: the paper's sum of two Gaussians
//   S(x) = a1 sqrt(pi/b1) exp(-pi^2 x^2/b1) + a2 sqrt(pi/b2) exp(-pi^2 x^2/b2), x in degrees,
//   evaluated at r^2 = x^2 + y^2 over a (2 radius + 1)^2 square and normalized to sum 1. A single
//   Gaussian separates into g(x) g(y); the blue-yellow sum of two separates into two passes with
//   weights sqrt(a sqrt(pi/b)) exp(-pi^2 x^2/b), normalized so that the 2-D kernel sums to 1.
// - feature kernels on the achromatic channel, Gaussian sigma = 0.5 w ppd pixels (w = 0.082 degrees)
//   over radius ceil(3 sigma): the Gaussian itself (normalized to sum 1), its first derivative
//   (edges) and its second derivative (points), each with the positive weights normalized to sum 1
//   and the negative ones to sum -1. The 2-D detector d/dx is edge(x) gaussian(y), and so on.
//
// Each kernel holds the weights for offsets 0..radius. All are symmetric, w(-j) = w(j), except
// `edge`, which is antisymmetric: w(-j) = -w(j), w(0) = 0. The reference correlates (weight at
// offset j multiplies the pixel at x + j); so does LdrFlip.
#pragma once

#include <vector>

namespace kdop::flip {

// The CSF of one channel in the paper's form (a2 = 0: a single Gaussian). b2 = 1e-5 where a2 = 0
// is the reference's guard against dividing by zero; it takes part in the radius's maximum.
struct CsfGaussians {
    double a1, b1, a2, b2;
};
inline constexpr CsfGaussians kCsfAchromatic{1.0, 0.0047, 0.0, 1e-5};
inline constexpr CsfGaussians kCsfRedGreen{1.0, 0.0053, 0.0, 1e-5};
inline constexpr CsfGaussians kCsfBlueYellow{34.1, 0.04, 13.5, 0.025};

// Width of the human edge detector's filter, peak to trough, in degrees (2 standard deviations).
inline constexpr double kFeatureWidthDegrees = 0.082;

struct CsfKernels {
    int radius = 0;
    std::vector<float> achromatic, red_green;        // Y and Cx: one Gaussian each
    std::vector<float> blue_yellow_1, blue_yellow_2; // Cz: the two separated Gaussians, to be added
};

struct FeatureKernels {
    int radius = 0;
    double sigma = 0; // pixels
    std::vector<float> gaussian, edge, point;
};

// ceil(3 sqrt(b_max / (2 pi^2)) ppd): three standard deviations of the widest Gaussian of any channel.
int csf_radius(double pixels_per_degree);
// ceil(3 sigma), sigma = 0.5 kFeatureWidthDegrees ppd.
int feature_radius(double pixels_per_degree);

// Both need pixels_per_degree >= 1 (below, the feature Gaussian's tails underflow to zero and
// its derivatives cannot be normalized); LdrFlip checks that.
CsfKernels make_csf_kernels(double pixels_per_degree);
FeatureKernels make_feature_kernels(double pixels_per_degree);

} // namespace kdop::flip
