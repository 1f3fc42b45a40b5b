// The stress suite (`kdop stress`): every selected variant, built in-process, run on the device
// over every stress case (stress_cases.h), each output checked pixel by pixel against the
// reference (stress_check.h).
#pragma once

#include "context.h"
#include "stress_check.h"
#include "variant_spec.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace kdop {

struct StressOptions {
    std::vector<VariantSpec> specs; // clips only
    std::uint64_t seed = 1;
    float gamma = 1.0f;             // for variance clips
};

struct StressRun {
    std::vector<std::string> variants;                       // rows
    std::vector<std::string> cases, case_descriptions;       // columns
    std::vector<std::vector<CheckResult>> results;           // [variant][case]
    std::string device_name, driver_info;

    std::size_t failing_cells() const;
};

// Called after each variant: how many are done, and the one just finished.
using StressProgress = std::function<void(std::size_t done, std::size_t total, const std::string& variant)>;

Result<StressRun> run_stress(const Context& context, const StressOptions& options, const StressProgress& progress = {});

} // namespace kdop
