// LDR-FLIP: the perceived difference between a reference and a test image when a viewer flips
// between them (Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom, Fairchild, "FLIP: A
// Difference Evaluator for Alternating Images", HPG 2020), per pixel in [0, 1], as its reference
// implementation (NVlabs/flip, C++ and Python) computes it. Where the paper leaves a detail to the
// code (matrices, white point, the 2-D form of the CSF, the separation of the filters, the
// achromatic channel's normalization, the mean), the code follows the reference and says so.
//
// Per pixel: both images go to YCxCz and are filtered with the contrast sensitivity of each
// channel (flip_filters.h); the filtered colors are clamped to [0, 1] in linear RGB, taken to
// Hunt-adjusted L*a*b*, and their HyAB distance, raised to qc = 0.7, is remapped to the color
// error dE_c in [0, 1] (the part below pc = 0.4 of the largest distance, green vs blue, goes to
// [0, pt = 0.95]). Edges and points of the achromatic channel (Gaussian derivatives) give the
// feature error dE_f = (max(|edge_r - edge_t|, |point_r - point_t|) / sqrt 2)^qf, qf = 0.5. The
// error is dE = dE_c^(1 - dE_f). The definition is symmetric in the two images.
//
// Inputs are LINEAR RGB in [0, 1] (kdop's convention); LDR-FLIP's own first step, sRGB to linear,
// is the caller's (flip::srgb_to_linear in color_spaces.h). Borders are clamp-to-edge, as in the
// reference. HDR-FLIP (exposures and tone mapping over HDR inputs) is hdr_flip.h.
#pragma once

#include "core/result.h"
#include "flip/flip_filters.h"
#include "images/image.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace kdop {

namespace flip {
// The paper's constants (and the reference's FLIPConstants): the color error's exponent qc, and
// its remapping: distances below pc cmax go to [0, pt], the rest to [pt, 1]; the feature
// error's exponent qf.
inline constexpr float kQc = 0.7f, kPc = 0.4f, kPt = 0.95f, kQf = 0.5f;
} // namespace flip

// The paper's default: a 0.7 m wide 3840-pixel display seen from 0.7 m.
struct ViewingConditions {
    double distance_m = 0.7, display_width_m = 0.7, display_width_px = 3840;
};

// distance * (pixels / width) * pi / 180: pixels per degree of visual angle at the display's
// center (the paper's small-angle formula; about 67.02 for the defaults).
double pixels_per_degree(const ViewingConditions& viewing);

// The range LdrFlip accepts. Below 1, the feature Gaussian (sigma = 0.041 ppd pixels) is too
// narrow to have derivatives at the next pixel; above 1000, kernels span hundreds of pixels.
inline constexpr double kMinPixelsPerDegree = 1.0, kMaxPixelsPerDegree = 1000.0;
Result<void> check_pixels_per_degree(double pixels_per_degree);

// Fails unless every pixel's R, G and B are finite and in [0, 1], naming `what` (e.g. "reference"
// or a file), the pixel and the value. Alpha is not looked at.
Result<void> check_ldr_image(const Image& image, const std::string& what);

// Per pixel, row-major: the color error, the feature error and their combination.
struct FlipTerms {
    std::vector<float> color, feature, error;
};

// A pair's mean FLIP and, where asked for, its error map (per pixel, row-major; empty otherwise).
struct FlipMap {
    double mean = 0;
    std::vector<float> error;
};

// At most the bytes one evaluation of a width x height pair allocates: its working planes (a ring
// of rows as tall as its filters, never more than the image) and the error map.
inline std::uint64_t ldr_flip_bytes(std::uint32_t width, std::uint32_t height) {
    return std::uint64_t(width) * height * (14 + 1) * sizeof(float);
}

// The mean of an error map, accumulated in double: what LdrFlip::mean reports for that map.
double mean_error(std::span<const float> error_map);

// Evaluates many image pairs at one ppd: the kernels are made once. Every method is const and
// keeps no state between calls, so one object serves any number of threads at once; each call
// allocates its working planes (14 floats per pixel of the rows its filters span) once, nothing per
// pixel.
class LdrFlip {
public:
    // Throws std::invalid_argument when check_pixels_per_degree fails (check it first for a message).
    explicit LdrFlip(double pixels_per_degree);

    double pixels_per_degree() const { return ppd_; }
    const flip::CsfKernels& csf_kernels() const { return csf_; }
    const flip::FeatureKernels& feature_kernels() const { return features_; }
    // The color error's remapping as evaluate() applies it, in float: cmax, the largest
    // exponentiated HyAB distance (green vs blue), and pc cmax, where the two ranges meet.
    float max_color_distance() const { return cmax_; }
    float pc_max_color_distance() const { return pccmax_; }

    // reference and test: linear RGB in [0, 1] (alpha ignored), the same size, not empty; anything
    // else is an error that names the image, the pixel and the value (nothing is clamped).
    Result<double> mean(const Image& reference, const Image& test) const;
    Result<std::vector<float>> error_map(const Image& reference, const Image& test) const;
    Result<FlipTerms> terms(const Image& reference, const Image& test) const;

private:
    Result<void> evaluate(const Image& reference, const Image& test, float* error, float* color, float* feature) const;

    double ppd_;
    flip::CsfKernels csf_;
    flip::FeatureKernels features_;
    float cmax_, pccmax_; // the largest exponentiated HyAB distance (green vs blue), and pc times it
};

} // namespace kdop
