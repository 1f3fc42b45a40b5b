// Fitting an axis set: the directions whose k-DOPs enclose a scene's neighborhoods most tightly
// (the paper's second claim: fitted axes reach the same anti-ghosting with fewer of them).
//
// Objective: the mean k-DOP volume over every neighborhood of the images (not a sample), or,
// scene-independent, the volume of the k-DOP around the unit sphere. Volume is the paper's
// objective; it is what the clip lets through beyond the colors seen, and its gradient in the
// axes is exact and cheap (fit/kdop_polytope.h), so the search follows it instead of sampling.
//
// Search: from several starts, projected gradient descent on the axes' unit sphere with an
// adaptive step (longer after a success, halved after a failure). Starts are seeded and the
// neighborhoods are summed in fixed chunks in a fixed order, so the result is the same for a seed
// on any number of threads; only a time limit, which stops the search where the machine got to,
// makes it depend on speed.
#pragma once

#include "fit/frame_neighborhoods.h"
#include "fit/kdop_polytope.h"
#include "fit/neighborhoods.h"

#include <kdop/variant.h>

#include <glm/vec3.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace kdop {

struct FitOptions {
    std::size_t axes = 8;
    bool force_rgb = false; // the first three axes are R, G and B and stay so
    std::uint64_t seed = 1;
    unsigned threads = 0;                                          // 0: one per core
    std::size_t starts = 0;                                        // 0: 64 around the sphere, 4 on images
    std::size_t iterations = 0;                                    // per start; 0: 400 around the sphere, 60 on images
    std::optional<std::chrono::steady_clock::time_point> deadline; // stop there with the best so far
};

struct FitResult {
    std::vector<glm::dvec3> axes; // unit, forced ones first
    double score = 0;             // the objective at `axes`
    std::size_t volumes = 0;      // k-DOP volumes in the objective (neighborhoods x evaluations)
    std::size_t computed = 0;     // of those, computed (a repeated neighborhood once per evaluation)
    std::size_t failed = 0;       // of the volumes, polytopes that could not be built (left out of means)
    double seconds = 0;
    bool stopped_early = false; // the deadline came first
};

// Called as the search goes: units done of total (starts around the sphere, steps on images, where
// each step is a pass over every neighborhood), and the best score so far.
using FitProgress = std::function<void(std::size_t done, std::size_t total, double best)>;

FitResult fit_to_sphere(const FitOptions& options, const FitProgress& progress = {});
FitResult fit_to_neighborhoods(const FrameNeighborhoods& neighborhoods, const FitOptions& options,
                               const FitProgress& progress = {});
FitResult fit_to_neighborhoods(const Neighborhoods& neighborhoods, const FitOptions& options,
                               const FitProgress& progress = {});

// One pixel of the distance objective (kdop optimize --objective distance): its neighborhood, its
// current and history colors, the point where the ideal clip (the neighborhood's hull) stops the
// history, and the pixel's magnitude S, the unit the distance is measured in (accuracy_metrics.h).
// accuracy/sampled_distance.h makes them.
struct ClipSample {
    std::vector<glm::dvec3> neighborhood;
    glm::dvec3 current{0.0}, history{0.0}, ideal{0.0};
    double scale = 1;
};

// The mean distance, in S, from the k-DOP clip of `axes` (unit) to the ideal clip over `samples`,
// and with `gradient` its gradient in the axes. The clip is the CPU reference's hardened one
// (reference/cpu_clip.h): the same figure kdop optimize reports as the distance.
double mean_clip_distance(std::span<const glm::dvec3> axes, std::span<const ClipSample> samples, unsigned threads = 0,
                          std::vector<glm::dvec3>* gradient = nullptr);

// Descends from `from` on that distance with its exact subgradient: where the exit slab of axis a
// stops the ray at t = a.(n* - c) / a.(h - c) (n* the neighbor setting the bound), dt/da =
// ((n* - c) - t (h - c)) / a.(h - c); the ideal clip does not depend on the axes. Only steps that
// lower the distance are taken, so the result is never farther than `from` on these samples.
// `options.iterations` (0: 60) steps; the starts are not used.
FitResult refine_for_distance(std::vector<glm::dvec3> from, std::span<const ClipSample> samples,
                              const FitOptions& options, const FitProgress& progress = {});

// The mean k-DOP volume of `axes` over the neighborhoods (polytopes that fail are left out and
// counted in `failed`), on `threads` threads in a fixed order.
double mean_volume(std::span<const glm::dvec3> axes, const Neighborhoods& neighborhoods, unsigned threads = 0,
                   std::size_t* failed = nullptr);
// The same for several sets in one pass over the frames (each frame read once for all of them).
std::vector<double> mean_volumes(std::span<const std::vector<glm::dvec3>> sets, const FrameNeighborhoods& frames,
                                 unsigned threads = 0);

// Components equal to 0 over all axes: what a clip spends multiply-adds on (a zero costs nothing).
std::size_t nonzero_components(std::span<const glm::dvec3> axes);

// Trading tightness for cost, as the supplement's 22-DOP does with its zeros: from a fitted set,
// pins its smallest component (relative to its axis's largest) at 0 and refits, one at a time,
// until at most `max_nonzero` components are left (or one per axis). Each step of the curve, the
// start first. On the neighborhoods, or around the sphere when `neighborhoods` is null.
struct SparserStep {
    std::size_t nonzero;
    double score;
    std::vector<glm::dvec3> axes;
};
std::vector<SparserStep> fit_sparser(const FrameNeighborhoods* neighborhoods, const FitResult& start,
                                     std::size_t max_nonzero, const FitOptions& options,
                                     const FitProgress& progress = {});

} // namespace kdop
