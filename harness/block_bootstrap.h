// How far a mean over frames could move on other frames like them: a percentile interval from a
// block bootstrap (Kunsch 1989; Efron and Tibshirani, "An Introduction to the Bootstrap", 8.6).
// TAA figures of neighboring frames are not independent (the history carries about 1 / w frames,
// w the current frame's weight), so frames are drawn in blocks of consecutive ones, not one by one,
// or the interval would come out too narrow.
//
// The figure is the one choose and taa report: the mean over sequences of each sequence's mean over
// its frames. A replicate draws, in each sequence, as many blocks as it has (its frames cut into
// consecutive blocks of `block`, the last one shorter where they do not divide), with replacement,
// and takes the figure of the frames drawn. Every candidate of one call is measured on the same
// frames, so each replicate's draw is applied to all of them (paired): the interval of a
// difference between two candidates then reflects how differently they fare on the same frames,
// which is much narrower than either one's own interval where both follow the content.
//
// The draw is fixed by this file: SplitMix64 (images/random.h) seeded with `seed`; replicate by
// replicate, sequence by sequence, block by block, the block drawn is next() % blocks. The same
// figures and options give the same intervals on every machine.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace kdop {

struct BootstrapOptions {
    std::size_t block = 10; // frames per block; a sequence of fewer than 2 blocks gives no interval
    std::size_t replicates = 2000;
    std::uint64_t seed = 1;
    double level = 0.95; // the interval's coverage: its ends are the (1 - level) / 2 and (1 + level) / 2 quantiles
};

// A percentile interval; NaN ends where none could be drawn.
struct Interval {
    double low = NAN, high = NAN;
    bool known() const { return !std::isnan(low) && !std::isnan(high); }
    bool holds(double x) const { return known() && low <= x && x <= high; }
};

// The replicates of each candidate's figure: `figures[candidate][sequence][frame]`. Every candidate
// must have the same number of frames in each sequence (they are paired frame by frame), and every
// sequence at least 2 blocks' worth; otherwise nothing is drawn (nullopt). Result: [candidate][replicate].
std::optional<std::vector<std::vector<double>>>
bootstrap_replicates(const std::vector<std::vector<std::vector<double>>>& figures, const BootstrapOptions& options);

// The frames of a block for a TAA resolve whose current frame weighs `current_weight`: ceil(1 / w),
// about how many frames its history averages (10 at kdop's default 0.1), so frames of one block
// share most of their history and frames of different blocks little.
std::size_t history_block(double current_weight);

// The interval of one candidate's replicates, and of a paired difference (a's minus b's).
Interval percentile_interval(const std::vector<double>& replicates, double level);
Interval difference_interval(const std::vector<double>& a, const std::vector<double>& b, double level);

} // namespace kdop
