// `kdop accuracy`'s run after its command line is read: the image pairs read or made, every
// variant's clip measured against the ideal clip on the device (accuracy_run.h), and the tables,
// report and Pareto charts written as one set of files.
#pragma once

#include "core/result.h"
#include "generator/variant_spec.h"
#include "harness/run_metadata.h"
#include "harness/variant_catalog.h"
#include "images/image_io.h"
#include "runtime/context.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace kdop {

// Which pairs are measured: one given pair, or `images` against the built-in ghosting histories,
// or (neither given) the built-in texture families at size x size (accuracy_inputs.h).
struct AccuracyContent {
    std::string current, history;
    std::vector<std::string> images;
    std::uint32_t size = 128;
    std::uint64_t seed = 1; // the built-in content's, and the volume sample's
    InputSpace input_space = InputSpace::from_file;
};

struct AccuracyStudyOptions {
    AccuracyContent content;
    std::filesystem::path out; // the output folder
    std::string cost;          // a `kdop bench` cost.csv adding lavapipe's cost to the trade table; or empty
    float gamma = 1.0f;        // the variance clips' slab half-width
    std::size_t volume_samples = 256;
    bool charts = true; // the Pareto charts (none where gnuplot is missing)
    ContextOptions device;
};

struct AccuracyStudySummary {
    std::size_t variants = 0, pairs = 0;
    RunMetadata run;
    std::filesystem::path report; // report.md
    std::vector<std::string> validation_messages;
};

// Measures `specs` (clips of `catalog`) and writes accuracy.csv, trade.csv (each also as JSON),
// report.md and the charts to options.out, all or nothing. Progress goes to stderr.
Result<AccuracyStudySummary> accuracy_study(const std::vector<VariantSpec>& specs, VariantCatalog& catalog,
                                            const AccuracyStudyOptions& options);

} // namespace kdop
