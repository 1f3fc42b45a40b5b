// Reading back the cost.csv `kdop bench` writes (cost_table.h), for `kdop accuracy --cost`: what
// each clip costs on lavapipe beyond its gather-only baseline.
#pragma once

#include "core/result.h"
#include "core/variant_key.h"

#include <cmath>
#include <filesystem>
#include <map>

namespace kdop {

// What `kdop bench` measured on lavapipe for a variant, beyond its gather-only baseline.
struct LavapipeCost {
    double marginal_instr_per_px = NAN; // callgrind: instr_per_px minus gather-<neighborhood>'s
    double marginal_ms = NAN;           // marginal_ms (a median: noisy)
};

// Reads a bench cost.csv (bench/README.md). Errors name the file and line.
Result<std::map<VariantKey, LavapipeCost>> read_bench_costs(const std::filesystem::path& cost_csv);

} // namespace kdop
