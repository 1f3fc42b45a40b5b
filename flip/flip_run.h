// `kdop flip`'s run after its command line is read: a reference and one or more test images read
// and checked, LDR-FLIP or HDR-FLIP of each test against the reference computed on the device (or
// the CPU's reference code) with the statistics NVlabs/flip's tool prints (flip_statistics.h),
// optionally timed; then the error map (and HDR-FLIP's exposure map), a CSV of the statistics and
// a picture of the weighted histograms written as one set of files.
#pragma once

#include "core/result.h"
#include "flip/flip_statistics.h"
#include "flip/hdr_flip.h"
#include "images/image_io.h"
#include "runtime/context.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kdop {

struct FlipRunOptions {
    std::string reference;
    std::vector<std::string> tests; // each against the reference, on one device
    double ppd = 0;                 // pixels per degree (check_pixels_per_degree's range)
    InputSpace input_space = InputSpace::from_file;
    bool hdr = false;         // HDR-FLIP instead of LDR-FLIP
    ExposureOptions exposure; // HDR-FLIP's
    bool cpu = false;         // the CPU's reference code instead of the device (the default where none is named)
    ContextOptions device;    // which device, and the validation layer
    int timing = 0;           // evaluations after the first, timed
    std::string out;          // one test's error map: .exr (values) or .png (magma); empty: none
    std::string exposure_map; // HDR-FLIP: which exposure gave each pixel's error; empty: none
    std::string csv;          // every test's statistics as a table; empty: none
    std::string histogram;    // every test's weighted histogram as a .png chart; empty: none
};

// One test image's figures.
struct FlipTestResult {
    std::string test;
    FlipStatistics statistics;
    std::vector<std::size_t> histogram;   // flip_histogram()'s counts
    ExposureRange range;                  // HDR-FLIP's exposures
    std::vector<float> map, exposure_map; // per pixel, where a file wants them
};

struct FlipRunResult {
    std::vector<FlipTestResult> tests; // in the order given
    std::uint32_t width = 0, height = 0;
    std::string space;  // how the inputs were decoded, as a clause (", every input taken as linear"), or empty
    std::string device; // the device's name; empty: on the CPU
    // On the CPU because no device was named (no --device, $KDOP_DEVICE or --validation): kdop's
    // default device, lavapipe, is a CPU, where the device passes are slower than the CPU code.
    bool cpu_by_default = false;
    std::vector<double> wall_s, cpu_s;        // per timed evaluation of the first test: its mean alone
    double setup_wall_s = 0, setup_cpu_s = 0; // the device and its passes' set-up
    std::vector<std::string> validation_messages;
};

// The evaluation of options check() accepts (flip_check.h; others are an error). The caller
// checks the files the options name before (cli/flip_command.cpp: none a folder, a special file or
// an input); write_atomically refuses an input again. Errors name the option and file.
Result<FlipRunResult> run_flip(const FlipRunOptions& options);

// `result`'s files (options.out, exposure_map, csv, histogram: those given), as one set: all or
// none.
Result<void> write_flip_outputs(const FlipRunOptions& options, const FlipRunResult& result);

} // namespace kdop
