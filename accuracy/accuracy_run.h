// The accuracy measurement (`kdop accuracy`): every selected variant run on the device over every
// image pair (through the harness's device runner) and in the CPU reference, each compared pixel
// by pixel with the ideal clip at the convex hull; plus k-DOP over hull volume on a sample of pixels.
#pragma once

#include "accuracy/accuracy_inputs.h"
#include "accuracy/accuracy_metrics.h"
#include "accuracy/volume_ratio.h"
#include "harness/device_runner.h"
#include "harness/progress.h"
#include "harness/variant_catalog.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kdop {

struct AccuracyOptions {
    std::vector<VariantKey> variants; // clips only
    float gamma = 1.0f;               // for variance clips
    std::size_t volume_samples = 256; // pixels per pair and neighborhood; 0: no volumes
    std::uint64_t seed = 1;           // of the volume sample
};

struct AccuracyRow {
    VariantKey key;
    unsigned k = 0;
    bool rgb_axes = false;     // the set contains the X, Y and Z axes, so its k-DOP lies inside the RGB AABB
    std::size_t float_ops = 0; // static cost of the built SPIR-V (spirv_cost.h)
    std::string family, image;
    ClipAccuracy gpu, reference;    // the device's output and the double-precision reference's
    double gpu_reference_max = NAN; // the largest |device - reference| / S: the device's float error
    // Against the RGB AABB of the same mode and neighborhood (NaN where aabb was not selected).
    Looser vs_aabb, reference_vs_aabb;
    VolumeRatio volume;
};

struct AccuracyRun {
    std::vector<AccuracyRow> rows; // pair-major, variants in selection order
};

// Progress advances as each step ends: per pair, the ideal clip of each neighborhood, then the variants.
Result<AccuracyRun> run_accuracy(DeviceRunner& runner, VariantCatalog& catalog, const AccuracyOptions& options,
                                 const std::vector<AccuracyPair>& pairs, Progress* progress = nullptr);

// How many progress steps run_accuracy reports for these options and pairs.
std::size_t accuracy_steps(const AccuracyOptions& options, std::size_t pairs);

} // namespace kdop
