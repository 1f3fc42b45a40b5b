// HDR-FLIP (Andersson, Nilsson, Shirley, Akenine-Moller, "Visualizing Errors in Rendered High
// Dynamic Range Images", Eurographics 2021) as its reference implementation (NVlabs/flip, FLIP.h)
// computes it: both images are exposed at a range of exposures, tone mapped, clamped to [0, 1], and
// compared with LDR-FLIP (flip.h); each pixel's error is its largest over the exposures. The paper's
// full text is not at hand here, so every detail follows the reference code and says where:
//
// - Tone mappers (FLIP.h toneMap, ToneMappingCoefficients): ACES (Narkowicz's fit with the 0.6
//   pre-exposure cancelled), Hable, each a per-channel rational (a x^2 + b x + c) / (d x^2 + e x + f);
//   Reinhard is color / (1 + luminance), per pixel.
// - The exposure range (computeExposures), from the reference alone: x_max solves T(x) = 0.85 for
//   the tone mapper's curve; start = log2(x_max / Y_max) and stop = log2(x_max / Y_median), with
//   Y the reference's luminance (0.2126 R + 0.7152 G + 0.0722 B), Y_max its largest and Y_median the
//   element at index n / 2 in sorted order (zeros included). The count, unless given, is
//   max(2, ceil(stop - start)); exposure i is start + i (stop - start) / (count - 1).
// - The exposure map (setMaxExposure): i / (count - 1) of the first exposure whose error is the
//   pixel's largest (0 where every error is 0).
//
// Where the reference divides by zero or overflows, this defines instead, and says so:
// - one exposure (count 1) is the start exposure alone;
// - a reference whose median luminance is 0 (at least half its pixels black) takes the median of its
//   pixels that are not black for the stop exposure;
// - a black reference (largest luminance 0) takes the range of the test image instead, and a black
//   pair is measured at exposure 0 (any exposure gives no error); without a test image it is
//   refused unless start and stop are given. ExposureRange::note says when either happened;
// - exposures beyond +-126 stops (a reference of 1e-40 or 1e38) are refused: 2^exposure would not
//   be a normal float;
// - the tone curves are evaluated so that no value overflows: above 1e18 a channel (for Reinhard,
//   the luminance) is at the curve's limit, computed from 1/x (for Reinhard, color / luminance), so
//   1e19 tone-maps to white as 1e6 does, and an exposed value beyond float is at the limit too.
#pragma once

#include "core/result.h"
#include "flip/flip.h"
#include "images/image.h"

#include <glm/vec3.hpp>

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

enum class ToneMapper { aces, hable, reinhard };
std::optional<ToneMapper> parse_tone_mapper(std::string_view name); // "aces", "hable", "reinhard"
const char* to_string(ToneMapper tone_mapper);

// (a x^2 + b x + c) / (d x^2 + e x + f) per channel (FLIP.h ToneMappingCoefficients). Reinhard's
// row is what computeExposures solves for it; its tone map itself is by luminance (tone_map).
struct ToneCurve {
    float a, b, c, d, e, f;
};
const ToneCurve& tone_curve(ToneMapper tone_mapper);

// The tone mapper applied to one linear RGB color times `scale` (2^exposure), not clamped (HDR-FLIP
// clamps after it); finite for every finite color and scale (see above).
glm::vec3 tone_map(ToneMapper tone_mapper, glm::vec3 color, float scale = 1.0f);

// What the user sets; what is not set is derived from the reference as the reference code derives it.
struct ExposureOptions {
    ToneMapper tone_mapper = ToneMapper::aces;
    std::optional<float> start, stop; // exposures in stops (the image is multiplied by 2^exposure)
    std::optional<int> count;         // at least 1
};

struct ExposureRange {
    float start = 0, stop = 0;
    int count = 0;
    std::string note;            // how the range departs from the reference code's derivation; empty where it does not
    float exposure(int i) const; // start + i (stop - start) / (count - 1); start when count is 1
};

// The exposures HDR-FLIP evaluates `reference` (and `test`, for a black reference) at. Errors name
// the option or the luminance that makes the range unusable (start above stop, a count below 1,
// exposures float cannot scale by).
Result<ExposureRange> exposure_range(const Image& reference, const ExposureOptions& options,
                                     const Image* test = nullptr);

// What an exposure range is derived from: an image's largest luminance (0.2126 R + 0.7152 G +
// 0.0722 B, in float, in that order) and its median, the element at n / 2 in sorted order; where
// that is not above 0 and the largest is, the median of the pixels above 0 instead.
struct Luminances {
    float largest = 0, median = 0;
    bool median_of_lit = false; // the median of the pixels that are not black (at least half are)
};
Luminances luminances_of(const Image& image);
// The same range from the luminances however found (on the device: flip/device_flip.h); `test`'s
// are asked for only where the reference is black, and may be null where there is no test image.
// Each is asked for at most once, and not at all where the options give both ends.
using LuminancesSource = std::function<Result<Luminances>()>;
Result<ExposureRange> exposure_range(const ExposureOptions& options, const LuminancesSource& reference,
                                     const LuminancesSource& test);

// Fails unless every pixel's R, G and B are finite and not negative, naming `what`, the pixel and
// the value. Alpha is not looked at.
Result<void> check_hdr_image(const Image& image, const std::string& what);

struct HdrFlipMaps {
    ExposureRange range;
    double mean = 0;             // of the error map, as mean_error computes it
    std::vector<float> error;    // per pixel, row-major: the largest LDR-FLIP over the exposures
    std::vector<float> exposure; // per pixel: i / (count - 1) of the exposure that gave it (0 for count 1)
};

// Evaluates image pairs at one ppd (the LDR-FLIP kernels are made once); const and stateless, so
// one object serves any number of threads.
class HdrFlip {
public:
    // Throws std::invalid_argument when check_pixels_per_degree fails (check it first for a message).
    explicit HdrFlip(double pixels_per_degree) : ldr_(pixels_per_degree) {}

    const LdrFlip& ldr() const { return ldr_; }

    // reference and test: linear RGB, finite, not negative, the same size, not empty; anything else
    // is an error naming the image, the pixel and the value.
    Result<HdrFlipMaps> maps(const Image& reference, const Image& test, const ExposureOptions& options) const;

    // The reference's step at one exposure: both images multiplied by 2^exposure, tone mapped and
    // clamped to [0, 1], as LDR-FLIP is then given them.
    static Image tone_mapped(const Image& image, ToneMapper tone_mapper, float exposure);

private:
    LdrFlip ldr_;
};

} // namespace kdop
