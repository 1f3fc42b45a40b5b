// Deterministic cost: the CPU instructions lavapipe executes for one dispatch, per pixel, counted
// by callgrind around that dispatch alone (kdop-dispatch-probe brackets it with client requests;
// LP_NUM_THREADS=0 keeps it on one thread). Unlike wall time the count repeats from run to run
// (within 0.002% here), so it is the figure to compare variants by on a noisy machine.
// valgrind is run as a program: it has no library interface.
#pragma once

#include "core/result.h"
#include "harness/progress.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace kdop::bench {

struct CallgrindSetup {
    std::filesystem::path probe;   // the kdop-dispatch-probe executable
    std::filesystem::path scratch; // a private directory for callgrind's files and logs
    std::uint32_t size = 256;      // the dispatch covers size x size pixels
    std::string device;            // passed on to the probe; empty: lavapipe
};

// A kernel to count: a registry variant, or another module with that variant's interface.
struct ProbeKernel {
    std::string name;            // what progress and errors call it; names its scratch files
    std::string variant;         // the registry variant whose interface (and module) the probe runs
    std::filesystem::path spirv; // this module instead of the variant's, if not empty
};

// Instructions per pixel for each kernel, `jobs` valgrind processes at a time.
Result<std::vector<double>> callgrind_instructions_per_pixel(const CallgrindSetup& setup,
                                                             const std::vector<ProbeKernel>& kernels, unsigned jobs,
                                                             Progress& progress);

} // namespace kdop::bench
