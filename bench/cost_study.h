// `kdop bench`'s run after its command line is read: the variants named or selected, the cost bench
// (cost_bench.h) on the device, and cost.csv (and JSON), report.md and the charts written as one
// set of files.
#pragma once

#include "bench/cost_bench.h"
#include "core/result.h"
#include "harness/run_metadata.h"
#include "harness/variant_catalog.h"

#include <filesystem>
#include <string>
#include <vector>

namespace kdop::bench {

// The clips `names` (unrolled, of `catalog`'s sets) as the bench measures them; no names: every
// clip of the catalog with `numerics`. Errors name `option` and the variant.
Result<std::vector<VariantKey>> bench_variants(const VariantCatalog& catalog, const std::vector<std::string>& names,
                                               Numerics numerics, const std::string& option = "--variants");

struct CostStudyOptions {
    BenchOptions bench; // its probe and scratch are filled in by cost_study
    std::filesystem::path out;
    bool charts = true; // the charts (none where gnuplot is missing)
};

struct CostStudySummary {
    std::size_t variants = 0, files = 0;
    RunMetadata run;
};

// Runs the bench and writes its files to options.out, all or nothing. The callgrind counts run
// kdop-dispatch-probe from `program_dir` (where kdop is installed beside it).
Result<CostStudySummary> cost_study(VariantCatalog& catalog, CostStudyOptions options,
                                    const std::filesystem::path& program_dir);

} // namespace kdop::bench
