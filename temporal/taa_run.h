// `kdop taa`'s run after its command line is read: the rectification timed on the device, every
// variant's TAA over every scene and sequence (taa_evaluation.h), the ghosting pictures, and the
// table, report and charts added to the output set and written.
#pragma once

#include "core/result.h"
#include "generator/variant_spec.h"
#include "harness/output_set.h"
#include "harness/ranks.h"
#include "harness/run_metadata.h"
#include "runtime/context.h"
#include "scenes/taa_scene.h"
#include "sequence/frame_source.h"
#include "temporal/taa_evaluation.h"
#include "temporal/taa_sources.h"

#include <kdop/variant.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace kdop {

struct TaaRunSettings {
    EvaluationOptions evaluation;
    std::uint32_t width = 0, height = 0;      // of kdop's scenes (--size); the rectification is timed at it
    unsigned timing_rounds = 15;              // interleaved dispatches per variant
    std::uint64_t seed = 1;                   // the scenes', for the report
    bool write_frames = false;                // every measured output under frames/<sequence>/<variant>/
    bool charts = true;                       // the trade charts (none where gnuplot is missing)
    std::size_t viewer_frames = 8;            // report.html's frames per sequence besides the worst; 0: no viewer
    std::optional<std::size_t> picture_frame; // a sequence's ghosting picture's frame; unset: the chosen one
};

// Measures `specs` (with `rectifiers`, their rectification passes, in the same order) over
// `sources` and writes taa.csv (and JSON), report.md, report.html with its viewer's frames, the
// pictures and charts through `outputs`.
// Returns the run's metadata, as the report states it.
// Under mpirun the sources are shared over `ranks` (taa_ranks.h): each rank measures its own, rank 0
// times every variant, gathers the rest and writes every output; the other ranks return without
// writing. A rank that fails stops all of them, with its error, before anything is written.
Result<RunMetadata> run_taa(const Context& context, const std::vector<VariantSpec>& specs,
                            std::span<const Variant* const> rectifiers, const TaaSources& sources,
                            const TaaRunSettings& settings, OutputSet& outputs, const Ranks& ranks = Ranks{});

} // namespace kdop
