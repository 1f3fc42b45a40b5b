// What a fit reads before it searches: its inputs (images and sequences), every neighborhood of this
// rank's share of their frames (MPI ranks share the frames; harness/ranks.h), and with a sample the
// sample, drawn on every rank and gathered whole on each.
#pragma once

#include "core/result.h"
#include "fit/frame_neighborhoods.h"
#include "harness/ranks.h"
#include "optimize/fit_inputs.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace kdop {

struct FitDataOptions {
    FitInputOptions input;
    Neighborhood neighborhood = Neighborhood::n9;
    std::optional<std::size_t> sample; // sampled neighborhoods to fit on, drawn with `seed`
    std::uint64_t seed = 1;
    std::optional<double> memory; // MB of neighborhoods held between passes; none: the default
    std::string out;              // a file the run writes, refused where it is one of the inputs; empty: none
};

struct FitData {
    FitInputs inputs;
    std::optional<FrameNeighborhoods> neighborhoods, sampled;

    // What the search sees: the sample where one is drawn, else every neighborhood; none around the sphere.
    const FrameNeighborhoods* fitted_to() const {
        return sampled ? &*sampled : neighborhoods ? &*neighborhoods : nullptr;
    }
};

// Reads the inputs' headers, refuses what cannot be gathered (more ranks than frames, a frame whose
// neighborhoods would not fit in memory), runs `before_frames` (a check that must stop the run
// before the reading does), then reads this rank's frames once. A frame a rank cannot read stops
// every rank with its error.
Result<FitData> read_fit_data(const FitDataOptions& options, const Ranks& ranks,
                              const std::function<Result<void>()>& before_frames = {});

// `threads`, or where 0 under mpirun, this machine's cores shared with the other ranks on it.
unsigned rank_threads(unsigned threads);

// What `run` returns, or where a frame could no longer be read mid-fit (FitInputError) its error,
// the other ranks, waiting in a collective, stopped (Ranks::abort).
template <class T, class Run>
Result<T> stop_ranks_on_lost_frame(const Ranks& ranks, Run&& run) {
    try {
        return run();
    } catch (const FitInputError& e) {
        if (ranks.size() > 1) ranks.abort(e.what());
        return fail(e.what());
    }
}

// What a volume fit minimizes on `data`, in words.
std::string fit_objective(const FitData& data, Neighborhood shape, const ColorMap& color_map);

} // namespace kdop
