// Dispatch timings of several kernels measured side by side: every round dispatches each kernel
// once, in an order rotated from round to round, so slow phases of a shared machine spread over
// all kernels instead of landing on whichever ran then. One warm-up dispatch per kernel first
// (drivers may finish compiling there).
#pragma once

#include "core/result.h"
#include "harness/progress.h"
#include "runtime/context.h"

#include <kdop/variant.h>

#include <cstdint>
#include <span>
#include <vector>

namespace kdop::bench {

struct TimingRun {
    std::vector<std::vector<double>> ms; // per kernel, one sample per round
    bool device_clock = false;           // timestamps around the dispatch; else submit-to-fence wall time
};

Result<TimingRun> time_interleaved(const Context& context, std::span<const Variant* const> kernels, std::uint32_t width,
                                   std::uint32_t height, unsigned rounds, Progress& progress);

} // namespace kdop::bench
