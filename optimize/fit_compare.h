// A fitted set beside the built-in ones, and the axis-set file that says how it was fitted: its
// volume on every neighborhood (a sampled fit's worth on all the data), the distance to the ideal
// clip on sampled pixels, a built-in set that lands closer, and the file's comment block.
#pragma once

#include "core/color_map.h"
#include "core/result.h"
#include "fit/axis_fit.h"
#include "harness/ranks.h"
#include "optimize/fit_data.h"
#include "optimize/optimize.h"
#include "optimize/optimize_tables.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace kdop {

// The fitted set ("this set") first, then every built-in set, each with its mean volume over
// `frames` (one pass over them), or around the unit sphere where `frames` is null.
std::vector<ComparedSet> compared_sets(const FrameNeighborhoods* frames, const std::vector<glm::dvec3>& fitted,
                                       unsigned threads);

// A sampled fit's score on the sample against its score on all the neighborhoods, in words.
std::string sample_line(const FitData& data, std::uint64_t seed, double on_sample, double on_all);

// The pixels the distance to the ideal clip is measured on (fit_distance_samples), agreed over the ranks.
Result<std::vector<ClipSample>> read_distance_samples(const OptimizeOptions& options, const FitData& data,
                                                      const Ranks& ranks);

// What the distance over `samples` pixels is, in words; empty with none.
std::string distance_measure(const OptimizeOptions& options, std::size_t samples);

// Each set's mean distance to the ideal clip over `samples` (none: left NaN).
void add_distances(std::vector<ComparedSet>& sets, const std::vector<ClipSample>& samples);

// A built-in set of no more axes than the fitted one (sets[0]) that lands closer to the ideal clip, in
// words; empty where none does.
std::string closer_warning(const std::vector<ComparedSet>& sets);

// What the file says of how its set was fitted.
struct FitRecord {
    std::string name;
    std::uint64_t seed = 1;
    std::size_t starts = 0, iterations = 0; // 0: the defaults
    bool force_rgb = false, stopped_early = false;
    std::optional<ColorMap> color_map; // the space fitted in; none around the sphere
    std::string objective;             // what was minimized, and its value for the set
    double score = 0;
    std::vector<std::string> notes; // after the objective: how it was sampled or refined, a strategy's table
    std::string distance_measure;   // empty where no distance was measured
    std::vector<ComparedSet> sets;  // compared_sets', with distances where measured
    std::string closer_warning;     // empty where none
};

// The axis-set file of `axes`: provenance, comment block, color map and axes.
Result<std::string> fitted_set_text(const FitRecord& record, std::span<const glm::dvec3> axes);

} // namespace kdop
