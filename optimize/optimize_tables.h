// The tables `kdop optimize` prints and keeps in the axis file's comments, declared as columns
// (harness/printed_table.h): the trade of each axis count tried (--target, --target-ghosting), the
// curve of components pinned at 0 (--max-nonzero), and the fitted set beside the built-in ones.
#pragma once

#include "harness/printed_table.h"
#include "temporal/metrics.h"

#include <glm/vec3.hpp>

#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace kdop {

// What a set's hardened clip costs: float ops as the generator counts them (analytic_cost.h), and
// with --lavapipe-cost the instructions per pixel lavapipe runs beyond the gather (callgrind).
struct ClipCost {
    std::size_t float_ops = 0;
    std::optional<double> lavapipe_instructions;
};

// One axis count tried: the fitted set's volume and, with --target-ghosting, its figures on each
// sequence in the order given, each by metric (temporal/metrics.h, NaN where not measured).
struct AxisCountRow {
    std::size_t axes = 0;
    double volume = 0;
    std::vector<std::vector<double>> figures;
    ClipCost cost;
};

// One step of pinning components at 0.
struct SparserRow {
    std::size_t nonzero = 0;
    double score = 0;
    ClipCost cost;
};

// A set beside the fitted one: its objective on the same content and, on images and sequences, its
// mean distance to the ideal clip on the sampled pixels (NaN where not measured).
struct ComparedSet {
    std::string name;
    std::vector<glm::dvec3> axes;
    double score = NAN, distance = NAN;
};

// For each of `sequences` sequences (0: none), a column of each metric `metrics` measures, the one
// ranked by first (ranking_first); `lavapipe`: the callgrind column.
PrintedColumns<AxisCountRow> axis_count_columns(const Metrics& metrics, std::size_t sequences, bool lavapipe);
PrintedColumns<SparserRow> sparser_columns(bool lavapipe);
// Each set's volume (and distance) with its ratio to `fitted`'s.
PrintedColumns<ComparedSet> compared_set_columns(const ComparedSet& fitted, bool with_distance);

} // namespace kdop
