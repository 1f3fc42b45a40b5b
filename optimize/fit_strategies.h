// How kdop optimize finds its set, on the data read (fit_data.h): a fixed axis count; the fewest
// axes that reach a volume or ghosting target; components pinned at 0 down to a count; and the
// volume fit refined on the distance to the ideal clip. The tables they print are kept for the file.
#pragma once

#include "core/result.h"
#include "fit/axis_fit.h"
#include "fit/frame_neighborhoods.h"
#include "optimize/optimize.h"
#include "optimize/set_evaluator.h"

#include <glm/vec3.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace kdop {

// The search: its options (axes set by each strategy), on these neighborhoods, or around the unit
// sphere where null.
struct FitSearch {
    const FrameNeighborhoods* fitted_to = nullptr;
    FitOptions fit;
};

// kdop optimize's search: its options, with the deadline time_limit sets from now.
FitSearch fit_search(const OptimizeOptions& options, const FrameNeighborhoods* fitted_to);

// The rows of the strategies' tables, each passed on as it is computed.
struct FitTable {
    std::vector<std::string> rows;
    OptimizeRows on_row;
    void add(std::string row);
};

// A set of `axes` axes.
FitResult fit_axis_count(const FitSearch& search, std::size_t axes);

// 3 (4 with force_rgb), 4, ... up to options.axes: the first whose volume reaches options.target or
// whose ghosting on every sequence reaches options.target_ghosting; none reaching it is an error.
Result<FitResult> fit_to_target(const OptimizeOptions& options, const FitSearch& search, const SetEvaluator& evaluator,
                                FitTable& table);

// `start` with components pinned at 0 one by one, refitted after each, to options.max_nonzero.
Result<FitResult> fit_sparser_set(const OptimizeOptions& options, const FitSearch& search,
                                  const SetEvaluator& evaluator, FitResult start, FitTable& table);

// The volume fit `start`, descended on the mean distance to the ideal clip over `samples`, from it
// and from each built-in set of as many axes (none with force_rgb): the best of them.
struct RefinedFit {
    FitResult fit;
    std::string line; // where the descent started and ended, in words
};
RefinedFit refine_on_distance(const FitSearch& search, const FitResult& start, const std::vector<ClipSample>& samples);

} // namespace kdop
