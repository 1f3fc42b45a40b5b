// The cost bench (`kdop bench`): static cost from each variant's SPIR-V, timings of every variant
// beside its loop form, its paper twin and the gather/copy baselines in one interleaved run, a
// size sweep, and callgrind instruction counts. Any variant the catalog knows can be measured: the
// built-in ones as embedded, a user's set or a paper twin as built in-process. See bench/README.md.
#pragma once

#include "bench/cost_table.h"
#include "core/result.h"
#include "harness/variant_catalog.h"
#include "runtime/context.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace kdop::bench {

using Size = std::pair<std::uint32_t, std::uint32_t>; // width, height

struct BenchOptions {
    std::vector<VariantKey> variants; // clips, unrolled; their loop forms and paper twins come along
    Size timing_size{1920, 1080};
    unsigned rounds = 15;          // dispatches per kernel at timing_size
    std::vector<Size> sweep_sizes; // empty: no sweep
    unsigned sweep_rounds = 5;
    bool callgrind = true;
    std::uint32_t callgrind_size = 256;
    unsigned jobs = 1;             // callgrind processes at a time
    std::string device;            // empty: lavapipe
    std::filesystem::path probe;   // kdop-dispatch-probe
    std::filesystem::path scratch; // private working directory
};

struct SweepResult {
    std::vector<std::string> kernels;
    std::vector<Size> sizes;
    std::vector<std::vector<double>> ms_median; // [size][kernel]
};

struct BenchResult {
    std::vector<CostRow> rows; // the variants in order, then gather-n9, gather-n5, copy
    SweepResult sweep;
    bool device_clock = false; // timings from timestamps (else submit-to-fence wall time)
};

// The kernels the sweep times: the baselines, every selected clip-n9 variant, and the loop form of
// the selected clip-n9 variant with the most axes.
std::vector<VariantKey> sweep_kernels(const std::vector<VariantKey>& variants, const VariantCatalog& catalog);

Result<BenchResult> run_cost_bench(const Context& context, VariantCatalog& catalog, const BenchOptions& options);

} // namespace kdop::bench
