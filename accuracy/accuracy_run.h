// The accuracy measurement (`kdop accuracy`): every selected variant, built in-process, run on the
// device over every image pair and in the CPU reference, each compared pixel by pixel with the
// ideal clip at the convex hull; plus k-DOP over hull volume on a sample of pixels.
#pragma once

#include "accuracy_inputs.h"
#include "accuracy_metrics.h"
#include "context.h"
#include "variant_spec.h"
#include "volume_ratio.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace kdop {

struct AccuracyOptions {
    std::vector<VariantSpec> specs; // clips only
    float gamma = 1.0f;             // for variance clips
    std::size_t volume_samples = 256; // pixels per pair and neighborhood; 0: no volumes
    std::uint64_t seed = 1;           // of the volume sample
};

struct AccuracyRow {
    std::string variant, axis_set, mode, neighborhood;
    unsigned k = 0;
    bool rgb_axes = false;     // the set contains the X, Y and Z axes, so its k-DOP lies inside the RGB AABB
    std::size_t float_ops = 0; // static cost of the built SPIR-V (spirv_cost.h)
    std::string family, image;
    ClipAccuracy gpu, reference;       // the device's output and the double-precision reference's
    double gpu_reference_max = NAN;    // the largest |device - reference| / S: the device's float error
    // Against the RGB AABB of the same mode and neighborhood (NaN where aabb was not selected).
    Looser vs_aabb, reference_vs_aabb;
    VolumeRatio volume;
};

struct AccuracyRun {
    std::vector<AccuracyRow> rows; // pair-major, variants in selection order
    std::string device_name, driver_info;
};

// Called as each step starts: the pair, and what is being done ("ideal n9", "variants").
using AccuracyProgress = std::function<void(const std::string& step)>;

Result<AccuracyRun> run_accuracy(const Context& context, const AccuracyOptions& options,
                                 const std::vector<AccuracyPair>& pairs, const AccuracyProgress& progress = {});

// How many progress steps run_accuracy reports for these options and pairs.
std::size_t accuracy_steps(const AccuracyOptions& options, std::size_t pairs);

} // namespace kdop
