#include "optimize/fit_check.h"

#include "core/builtin_sets.h"
#include "core/variant_key.h"

#include <filesystem>

namespace kdop {

std::optional<FitConflict> check(const OptimizeOptions& o) {
    if (o.objective == OptimizeOptions::Objective::distance && o.accuracy_samples == 0)
        return FitConflict::distance_without_samples;
    if (o.lavapipe_cost && !o.target && !o.target_ghosting && !o.max_nonzero) return FitConflict::cost_without_table;
    if (o.force_rgb && o.axes <= 3) return FitConflict::rgb_fills_axes;
    if (o.max_nonzero && *o.max_nonzero < o.axes) return FitConflict::nonzero_below_axes;
    const std::string name = set_name(o);
    if (!is_valid_set_name(name)) return FitConflict::not_a_set_name;
    if (is_builtin_set(name)) return FitConflict::builtin_set_name;
    return std::nullopt;
}

std::optional<FitConflict> check_ranks(const OptimizeOptions& o, int rank_count) {
    if (o.sphere && rank_count > 1) return FitConflict::sphere_over_ranks;
    return std::nullopt;
}

std::string set_name(const OptimizeOptions& o) {
    return o.name.empty() ? std::filesystem::path(o.out).stem().string() : o.name;
}

} // namespace kdop
