// How far taa.csv's figures could move on other frames like these: each row's shimmer and ghosting
// with a block-bootstrap interval over its measured frames (harness/block_bootstrap.h, the one kdop
// choose gives its held-out ghosting), and whether each variant's ghosting is within noise of the
// least in its scene or sequence, as ms_noise says it of time. The variants of one scene are
// measured on the same frames, so each replicate draws the same blocks for all of them and a
// difference is judged on the same frames (paired).
#pragma once

#include "harness/block_bootstrap.h"
#include "temporal/taa_report.h"

#include <vector>

namespace kdop {

// Fills every row's interval of each of the first `metrics` metrics, and its within_noise, from
// `frames`, its per-frame figures (taa_frames.csv's rows). A scene or sequence with fewer than two
// blocks of measured frames of a metric gets none.
void add_intervals(std::vector<TaaRow>& rows, const std::vector<TaaFrameRow>& frames, std::size_t metrics,
                   const BootstrapOptions& options);

} // namespace kdop
