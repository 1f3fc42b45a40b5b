// The cost bench (`kdop bench`): static cost from the shipped SPIR-V, lavapipe timings of every
// variant beside its loop form and the gather/copy baselines in one interleaved run, a size
// sweep, and callgrind instruction counts. See bench/README.md for what each figure means.
#pragma once

#include "cost_table.h"
#include "result.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace kdop::bench {

using Size = std::pair<std::uint32_t, std::uint32_t>; // width, height

struct BenchOptions {
    std::vector<std::string> variants; // unrolled default variants; their loop forms come along
    Size timing_size{1920, 1080};
    unsigned rounds = 15;              // dispatches per kernel at timing_size
    std::vector<Size> sweep_sizes;     // empty: no sweep
    unsigned sweep_rounds = 5;
    bool callgrind = true;
    std::uint32_t callgrind_size = 256;
    unsigned jobs = 1;                 // callgrind processes at a time
    std::string device;                // empty: lavapipe
    std::filesystem::path probe;       // kdop-dispatch-probe
    std::filesystem::path scratch;     // private working directory
};

struct SweepResult {
    std::vector<std::string> kernels;
    std::vector<Size> sizes;
    std::vector<std::vector<double>> ms_median; // [size][kernel]
};

struct BenchResult {
    std::vector<CostRow> rows; // the variants in order, then gather-n9, gather-n5, copy
    SweepResult sweep;
    std::string device_name, driver_info;
    bool device_clock = false; // timings from timestamps (else submit-to-fence wall time)
};

// The kernels the sweep times: the baselines, every selected clip-n9 variant, dop32's loop form.
std::vector<std::string> sweep_kernels(const std::vector<std::string>& variants);

Result<BenchResult> run_cost_bench(const BenchOptions& options);

} // namespace kdop::bench
