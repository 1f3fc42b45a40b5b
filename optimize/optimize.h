// kdop optimize's run, apart from its command line: fit an axis set to a scene's images and frame
// sequences (every neighborhood, or a sample) or around the unit sphere, optionally the fewest axes
// that reach a volume or a ghosting target, or with components pinned at 0; compare it with the
// built-in sets (volume, and the distance to the ideal clip on sampled pixels); and write it as an
// axis-set file every command reads. Over MPI ranks (harness/ranks.h) each rank reads and
// evaluates its share of the frames; the result is the same for any rank or thread count.
#pragma once

#include "core/result.h"
#include "fit/axis_fit.h"
#include "harness/ranks.h"
#include "optimize/fit_inputs.h"
#include "optimize/optimize_tables.h"
#include "temporal/resolve_options.h"

#include <kdop/variant.h>

#include <glm/vec3.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace kdop {

struct OptimizeOptions {
    enum class Objective {
        volume,  // the mean k-DOP volume over every neighborhood
        distance // then refined on the mean distance to the ideal clip over the sampled pixels
    };

    FitInputOptions input; // images and sequences, their decoding and the fit's color space
    bool sphere = false;   // fit around the unit sphere instead: no input
    std::size_t axes = 0;  // with a target, the most to try
    bool force_rgb = false;
    Neighborhood neighborhood = Neighborhood::n9;
    std::string out;  // the axis-set file to write
    std::string name; // the set's name; empty: out's stem
    std::uint64_t seed = 1;
    std::size_t starts = 0, iterations = 0; // 0: the fit's defaults
    unsigned threads = 0;                   // 0: every core, shared with the other ranks on the machine
    double time_limit = 0;                  // seconds; 0: none
    std::optional<double> target;           // the fewest axes whose mean volume reaches it
    std::optional<double> target_ghosting;  // the fewest axes whose ghosting on every sequence reaches it
    ResolveOptions resolve;                 // of target_ghosting's measurement; its color map is input's
    std::uint32_t warmup = 100;             // frames of each sequence before target_ghosting measures
    std::optional<std::size_t> max_nonzero; // then components pinned at 0 until at most this many are left
    bool lavapipe_cost = false;             // tables count each row's clip on lavapipe (callgrind) too
    std::size_t accuracy_samples = 8192;    // pixels per input the distance is measured on; 0: none
    std::optional<double> memory;           // MB of neighborhoods held between passes
    std::optional<std::size_t> sample;      // fit on this many sampled neighborhoods, then score on all
    Objective objective = Objective::volume;
};

struct OptimizeResult {
    std::string file;              // the axis-set file written to options.out
    FitResult fit;                 // the fitted axes, and the search's time and counts
    std::string fitted_objective;  // what was minimized, in words
    double fitted_score = 0;       // its value for the written set
    std::string sample_line;       // with a sample: its score against the score on all
    std::string refined_line;      // with the distance objective: where the descent started and ended
    std::string distance_measure;  // empty where no distance was measured
    std::vector<ComparedSet> sets; // the fitted set ("this set") first, then every built-in set
    std::string closer_warning;    // a built-in set of no more axes closer to the ideal clip, else empty
    std::size_t own_frames = 0, held_frames = 0, frames = 0; // this rank's frames, those held, all
};

// A row of a --target, --target-ghosting or --max-nonzero table, as it is computed.
using OptimizeRows = std::function<void(const std::string& row)>;

// The whole run, in its stages: reads (fit_data.h), fits (fit_strategies.h, the sets costed and
// measured by set_evaluator.h), compares and writes options.out (rank 0; fit_compare.h). The options
// must pass check() and check_ranks() (fit_check.h), which the command line words; an error with
// `usage` set is still the command line's fault (more ranks than frames, an input as --out). Every
// rank returns the same result. A frame a rank can no longer read mid-fit stops every rank
// (Ranks::abort).
Result<OptimizeResult> optimize(const OptimizeOptions& options, const Ranks& ranks, const OptimizeRows& on_row = {});

} // namespace kdop
