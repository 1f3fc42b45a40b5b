// What one axis set's clip costs on lavapipe, counted by callgrind as the bench counts it: the
// instructions per pixel of its hardened clip pass beyond the gather-only pass of the same
// neighborhood (the bench's marginal_instr_per_px). For a set that exists only in memory, such as
// each step of `kdop optimize --max-nonzero`'s curve: the variant is built in-process and run by
// the probe with the interface of the RGB box's clip, which every clip of a neighborhood shares.
#pragma once

#include "bench/callgrind.h"
#include "core/result.h"
#include "generator/axis_set.h"
#include "harness/progress.h"

#include <kdop/variant.h>

namespace kdop::bench {

Result<double> marginal_clip_instructions(const AxisSet& set, Neighborhood neighborhood, const CallgrindSetup& setup,
                                          Progress& progress);

} // namespace kdop::bench
