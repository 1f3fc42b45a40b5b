// `kdop stress`'s run after its command line is read: every variant over the extreme cases on the
// device (stress_suite.h), checked against the reference, and with an output folder the stress
// table and report written as one set of files.
#pragma once

#include "core/result.h"
#include "generator/variant_spec.h"
#include "harness/run_metadata.h"
#include "harness/variant_catalog.h"
#include "runtime/context.h"
#include "stress/stress_suite.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace kdop {

struct StressStudyOptions {
    std::filesystem::path out; // stress.csv, stress.json and report.md; empty: none
    std::uint64_t seed = 1;
    float gamma = 1.0f; // the variance clips' slab half-width
    ContextOptions device;
};

struct StressStudy {
    StressRun run;
    RunMetadata run_info;
    std::vector<std::string> validation_messages;
};

// Stresses `specs` (clips of `catalog`), with a progress line on stderr. A broken invariant is a
// finding (StressRun::failing_cells), not an error.
Result<StressStudy> stress_study(const std::vector<VariantSpec>& specs, VariantCatalog& catalog,
                                 const StressStudyOptions& options);

} // namespace kdop
