// The stress suite (`kdop stress`): every selected variant run on the device over every stress
// case (stress_cases.h) through the harness's device runner, each output checked pixel by pixel
// against the reference (stress_check.h). What runs and how is the harness's; the cases and the
// invariants are this folder's.
#pragma once

#include "harness/device_runner.h"
#include "harness/progress.h"
#include "harness/variant_catalog.h"
#include "stress/stress_check.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kdop {

struct StressOptions {
    std::vector<VariantKey> variants; // clips only
    std::uint64_t seed = 1;
    float gamma = 1.0f; // for variance clips
};

struct StressRun {
    std::vector<std::string> variants;                 // rows
    std::vector<std::string> cases, case_descriptions; // columns
    std::vector<std::vector<CheckResult>> results;     // [variant][case]

    std::size_t failing_cells() const;
};

// Progress advances once per axis set and case.
std::size_t stress_steps(const StressOptions& options);

Result<StressRun> run_stress(DeviceRunner& runner, VariantCatalog& catalog, const StressOptions& options,
                             Progress* progress = nullptr);

} // namespace kdop
