// What kdop optimize's options say of themselves before anything is read: the options that do not
// go together, in the fit's own terms. Pure (no file is looked at); the command line words each
// conflict with the flags it took them from (cli/optimize_command.cpp).
#pragma once

#include "optimize/optimize.h"

#include <optional>
#include <string>

namespace kdop {

enum class FitConflict {
    distance_without_samples, // the distance objective with no pixels (accuracy_samples 0) to take it on
    cost_without_table,       // lavapipe_cost with no target, target_ghosting or max_nonzero table to count
    rgb_fills_axes,           // force_rgb fixes 3 axes, and axes leaves none to fit
    nonzero_below_axes,       // max_nonzero below axes: each axis keeps at least one component
    not_a_set_name,           // set_name() is not a set name
    builtin_set_name,         // set_name() is a built-in set's, which every command would take instead
    sphere_over_ranks,        // a sphere fit has no frames to share over more than one rank
};

// The first conflict of the options alone (sphere_over_ranks is check_ranks'), or none.
std::optional<FitConflict> check(const OptimizeOptions& options);

// The run's options against the ranks it is started on: sphere_over_ranks, or none.
std::optional<FitConflict> check_ranks(const OptimizeOptions& options, int rank_count);

// The set's name: options.name, else the stem of options.out.
std::string set_name(const OptimizeOptions& options);

} // namespace kdop
