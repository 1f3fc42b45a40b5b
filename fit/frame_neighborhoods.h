// The content a fit reads, frame by frame: images and the frames of sequences, each read only when
// it is needed. A studio's fit is to hundreds of captured 1080p frames, whose neighborhoods (216
// bytes a pixel, 450 MB a frame) cannot all be held; so each frame is gathered on its own, frames
// are held while they fit in a memory budget, and the rest are read and gathered again on every
// pass of the search. Peak memory is then the held frames plus one frame, whatever the count.
//
// The objective is summed frame by frame in frame order (each frame's sum in fixed chunks,
// axis_fit.cpp), so it is the same figure whether a frame was held or read again, on any number
// of threads, and on any number of processes: a process evaluates its own range of frames and
// `share` (an MPI all-gather, harness/ranks.h) hands every process every frame's sums before they
// are added up in frame order.
#pragma once

#include "core/result.h"
#include "fit/neighborhoods.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace kdop {

// One frame of a fit's content.
struct FitFrame {
    std::string label;                   // what an error names: the file
    std::uint64_t pixels = 0;            // width x height, known before the frame is read
    std::function<Result<Image>()> load; // its colors in the fit's space, checked (finite, 3x3 or more)
};

// A frame that read well on the first pass and not on a later one (changed on disk since): the
// search cannot go on without it. Thrown from the objective, caught by the command.
struct FitInputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Where a process's frames are and how frame sums reach every process: [first, end) are the
// frames this process reads; `share` receives every frame's sums (`per_frame` doubles each, the
// frames of other processes zero) and fills in the others'. One process: all frames, no sharing.
struct FrameShare {
    std::size_t first = 0, end = SIZE_MAX;
    std::function<void(std::span<double> sums, std::size_t per_frame)> share;
};

class FrameNeighborhoods {
public:
    // Neighborhoods already gathered, as one held frame.
    explicit FrameNeighborhoods(Neighborhoods held);

    // Reads each of this process's frames once (`on_frame` with each image, as read), gathering its
    // neighborhoods; they are kept while the kept ones take at most `budget` bytes, and gathered
    // again on each visit beyond that. Fails with the first frame that cannot be read.
    static Result<FrameNeighborhoods> gather(std::vector<FitFrame> frames, Neighborhood shape, std::uint64_t budget,
                                             FrameShare share = {},
                                             const std::function<void(std::size_t, const Image&)>& on_frame = {});

    std::size_t frame_count() const { return frames_.size(); }
    std::size_t own_frames() const { return share_.end - share_.first; } // this process's
    std::size_t held_frames() const;                                     // of those, held
    // Neighborhoods of all frames (every process's), repeats included.
    std::size_t count() const { return total_; }
    const FrameShare& share() const { return share_; }

    // Calls visit(frame, its neighborhoods) for each of this process's frames, in frame order.
    // Throws FitInputError when a frame gathered again can no longer be read.
    void visit(const std::function<void(std::size_t, const Neighborhoods&)>& visit) const;

private:
    FrameNeighborhoods() = default;
    std::vector<FitFrame> frames_;
    std::vector<Neighborhoods> held_; // by frame; empty where a frame is gathered on each visit
    std::vector<bool> is_held_;
    mutable Neighborhoods scratch_; // where a frame that is not held is gathered on each visit
    std::uint64_t held_bytes_ = 0;
    std::size_t total_ = 0;
    Neighborhood shape_ = Neighborhood::n9;
    FrameShare share_;
};

// The bytes one frame's gathered neighborhoods take at most (no repeats): points and counts.
std::uint64_t neighborhood_bytes(std::uint64_t pixels, Neighborhood shape);

} // namespace kdop
