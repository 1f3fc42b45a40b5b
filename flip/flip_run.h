// `kdop flip`'s run after its command line is read: two images read and checked, LDR-FLIP or
// HDR-FLIP computed on the device (or the CPU's reference code), optionally timed, and the error
// map (and HDR-FLIP's exposure map) written as one set of files.
#pragma once

#include "core/result.h"
#include "flip/hdr_flip.h"
#include "images/image_io.h"
#include "runtime/context.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kdop {

struct FlipRunOptions {
    std::string reference, test;
    double ppd = 0; // pixels per degree (check_pixels_per_degree's range)
    InputSpace input_space = InputSpace::from_file;
    bool hdr = false;         // HDR-FLIP instead of LDR-FLIP
    ExposureOptions exposure; // HDR-FLIP's
    bool cpu = false;         // the CPU's reference code instead of the device
    ContextOptions device;    // which device, and the validation layer
    int timing = 0;           // evaluations after the first, timed
    std::string out;          // the error map: .exr (values) or .png (magma); empty: none
    std::string exposure_map; // HDR-FLIP: which exposure gave each pixel's error; empty: none
};

struct FlipRunResult {
    double mean = 0;
    ExposureRange range; // HDR-FLIP's exposures
    std::uint32_t width = 0, height = 0;
    std::string space;  // how the inputs were decoded, as a clause (", every input taken as linear"), or empty
    std::string device; // the device's name; empty: on the CPU
    std::vector<double> wall_s, cpu_s;        // per timed evaluation
    double setup_wall_s = 0, setup_cpu_s = 0; // the device and its passes' set-up
    std::vector<std::string> validation_messages;
    std::vector<float> map, exposure_map; // per pixel, where a file wants them
};

// The evaluation, with every file checked before it. Errors name the option and file;
// Error::usage where the command line is at fault.
Result<FlipRunResult> run_flip(const FlipRunOptions& options);

// `result`'s maps to options.out and options.exposure_map (those given), as one set of files: both
// or neither.
Result<void> write_flip_maps(const FlipRunOptions& options, const FlipRunResult& result);

} // namespace kdop
