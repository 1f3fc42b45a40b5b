#include "fit/axis_fit.h"

#include "core/parallel_for.h"
#include "generator/axis_set.h"
#include "generator/variant_spec.h"
#include "images/random.h"
#include "reference/cpu_clip.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

namespace kdop {
namespace {

using Clock = std::chrono::steady_clock;

// Neighborhoods are summed in chunks of this many, each on one thread, and the chunks' sums added
// in chunk order: the same floating-point sum on any number of threads.
constexpr std::size_t kChunk = 2048;

// The objective and its gradient at `axes`.
struct Evaluation {
    double value = 0;
    std::vector<glm::dvec3> gradient;
    std::size_t volumes = 0, computed = 0, failed = 0;
};

void add_to(Evaluation& total, const Evaluation& e) {
    total.value += e.value;
    total.volumes += e.volumes;
    total.computed += e.computed;
    total.failed += e.failed;
    for (std::size_t i = 0; i < total.gradient.size(); ++i) total.gradient[i] += e.gradient[i];
}

// The objective's sums over one frame's neighborhoods (not yet divided by the count), in chunks
// each summed on one thread and added in chunk order.
Evaluation sum_neighborhoods(std::span<const glm::dvec3> axes, const Neighborhoods& neighborhoods, unsigned threads) {
    const KdopPolytope kdop(axes);
    const std::size_t chunks = (neighborhoods.distinct() + kChunk - 1) / kChunk;
    std::vector<Evaluation> partial(chunks);
    parallel_for(chunks, threads, [&](std::size_t c) {
        Evaluation& e = partial[c];
        e.gradient.assign(axes.size(), glm::dvec3(0.0));
        const std::size_t end = std::min(neighborhoods.distinct(), (c + 1) * kChunk);
        for (std::size_t i = c * kChunk; i < end; ++i) {
            const std::uint32_t repeats = neighborhoods.repeats[i];
            const double v = kdop.volume_gradient(neighborhoods.at(i), e.gradient, repeats);
            e.volumes += repeats;
            ++e.computed;
            if (std::isnan(v))
                e.failed += repeats;
            else
                e.value += repeats * v;
        }
    });
    Evaluation total;
    total.gradient.assign(axes.size(), glm::dvec3(0.0));
    for (const Evaluation& e : partial) add_to(total, e);
    return total;
}

// Sums to means: over the volumes that could be computed.
Evaluation& divide(Evaluation& e) {
    const double counted = static_cast<double>(std::max<std::size_t>(e.volumes - e.failed, 1));
    e.value /= counted;
    for (glm::dvec3& g : e.gradient) g /= counted;
    return e;
}

Evaluation evaluate_neighborhoods(std::span<const glm::dvec3> axes, const Neighborhoods& neighborhoods,
                                  unsigned threads) {
    Evaluation e = sum_neighborhoods(axes, neighborhoods, threads);
    return divide(e);
}

// Each frame's sums as doubles (exact for counts below 2^53), the layout FrameShare hands around:
// value, volumes, computed, failed, then the gradient.
constexpr std::size_t kPackedCounts = 4;
void pack(const Evaluation& e, double* out) {
    out[0] = e.value, out[1] = double(e.volumes), out[2] = double(e.computed), out[3] = double(e.failed);
    for (std::size_t i = 0; i < e.gradient.size(); ++i)
        for (int c = 0; c < 3; ++c) out[kPackedCounts + 3 * i + c] = e.gradient[i][c];
}
Evaluation unpack(const double* in, std::size_t axes) {
    Evaluation e;
    e.value = in[0], e.volumes = std::size_t(in[1]), e.computed = std::size_t(in[2]), e.failed = std::size_t(in[3]);
    e.gradient.resize(axes);
    for (std::size_t i = 0; i < axes; ++i)
        for (int c = 0; c < 3; ++c) e.gradient[i][c] = in[kPackedCounts + 3 * i + c];
    return e;
}

// Each set's sums over every frame (this process's frames read once, for all the sets), shared
// with the other processes, and added up in frame order.
std::vector<Evaluation> evaluate_frames(std::span<const std::vector<glm::dvec3>> sets, const FrameNeighborhoods& frames,
                                        unsigned threads) {
    std::size_t stride = 0;
    for (const std::vector<glm::dvec3>& axes : sets) stride += kPackedCounts + 3 * axes.size();
    std::vector<double> sums(frames.frame_count() * stride, 0.0);
    frames.visit([&](std::size_t frame, const Neighborhoods& neighborhoods) {
        double* out = sums.data() + frame * stride;
        for (const std::vector<glm::dvec3>& axes : sets) {
            pack(sum_neighborhoods(axes, neighborhoods, threads), out);
            out += kPackedCounts + 3 * axes.size();
        }
    });
    if (frames.share().share) frames.share().share(sums, stride);
    std::vector<Evaluation> totals;
    for (const std::vector<glm::dvec3>& axes : sets) totals.push_back({0, std::vector(axes.size(), glm::dvec3(0.0))});
    for (std::size_t frame = 0; frame < frames.frame_count(); ++frame) {
        const double* in = sums.data() + frame * stride;
        for (std::size_t s = 0; s < sets.size(); ++s) {
            add_to(totals[s], unpack(in, sets[s].size()));
            in += kPackedCounts + 3 * sets[s].size();
        }
    }
    for (Evaluation& e : totals) divide(e);
    return totals;
}

Evaluation evaluate_frames(std::span<const glm::dvec3> axes, const FrameNeighborhoods& frames, unsigned threads) {
    const std::vector<glm::dvec3> set(axes.begin(), axes.end());
    return std::move(evaluate_frames({&set, 1}, frames, threads)[0]);
}

// The k-DOP clip of one sample, as the CPU reference's hardened clip computes it (cpu_clip.h: the
// slabs padded by kReferencePadding, an unusable history dropped), and its distance to the ideal
// clip, with the distance's gradient in the axes added to `gradient` (see refine_for_distance).
double clip_distance(std::span<const glm::dvec3> axes, const ClipSample& s, std::vector<glm::dvec3>* gradient) {
    if (!reference_history_usable(s.current, s.history)) return glm::distance(s.current, s.ideal) / s.scale;
    const glm::dvec3 ray = s.history - s.current;
    double t = 1;
    std::size_t exit_axis = axes.size();
    glm::dvec3 bound{0.0}; // the neighbor setting the exit axis' bound
    for (std::size_t i = 0; i < axes.size(); ++i) {
        const double along = glm::dot(axes[i], ray);
        if (along == 0) continue; // parallel to the slab: it never exits
        // The bound the ray heads for: the highest projection going up, the lowest going down.
        const glm::dvec3* extreme = &s.neighborhood[0];
        for (const glm::dvec3& n : s.neighborhood)
            if (along > 0 ? glm::dot(axes[i], n) > glm::dot(axes[i], *extreme)
                          : glm::dot(axes[i], n) < glm::dot(axes[i], *extreme))
                extreme = &n;
        const double padding = along > 0 ? kReferencePadding : -kReferencePadding;
        const double exit = (glm::dot(axes[i], *extreme - s.current) + padding) / along;
        if (exit < t) t = std::max(exit, 0.0), exit_axis = i, bound = *extreme;
    }
    const glm::dvec3 miss = s.current + t * ray - s.ideal;
    const double distance = glm::length(miss);
    if (gradient && exit_axis < axes.size() && distance > 0 && t > 0) {
        const glm::dvec3& a = axes[exit_axis];
        const glm::dvec3 dt = ((bound - s.current) - t * ray) / glm::dot(a, ray);
        (*gradient)[exit_axis] += glm::dot(miss / distance, ray) / s.scale * dt;
    }
    return distance / s.scale;
}

Evaluation evaluate_clip_samples(std::span<const glm::dvec3> axes, std::span<const ClipSample> samples,
                                 unsigned threads) {
    const std::size_t chunks = (samples.size() + kChunk - 1) / kChunk;
    std::vector<Evaluation> partial(chunks);
    parallel_for(chunks, threads, [&](std::size_t c) {
        Evaluation& e = partial[c];
        e.gradient.assign(axes.size(), glm::dvec3(0.0));
        for (std::size_t i = c * kChunk; i < std::min(samples.size(), (c + 1) * kChunk); ++i)
            e.value += clip_distance(axes, samples[i], &e.gradient);
    });
    // Summed in chunk order, so the result does not depend on the thread count.
    Evaluation total;
    total.gradient.assign(axes.size(), glm::dvec3(0.0));
    for (const Evaluation& e : partial) {
        total.value += e.value;
        for (std::size_t i = 0; i < axes.size(); ++i) total.gradient[i] += e.gradient[i];
    }
    const double count = double(std::max<std::size_t>(samples.size(), 1));
    total.value /= count;
    for (glm::dvec3& g : total.gradient) g /= count;
    total.volumes = total.computed = samples.size();
    return total;
}

Evaluation evaluate_sphere(std::span<const glm::dvec3> axes) {
    Evaluation e;
    e.gradient.assign(axes.size(), glm::dvec3(0.0));
    e.value = KdopPolytope(axes).sphere_volume_gradient(e.gradient);
    e.volumes = e.computed = 1;
    if (std::isnan(e.value)) {
        e.failed = 1;
        e.value = std::numeric_limits<double>::infinity();
    }
    return e;
}

glm::dvec3 random_direction(Random& random) {
    for (;;) { // uniform in the unit ball, then projected: uniform on the sphere
        const glm::dvec3 p(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
        const double length = glm::length(p);
        if (length > 1e-3 && length <= 1) return p / length;
    }
}

// Start `index` of a search with `seed`: the forced axes, then random directions. Each start has
// its own generator, so starts do not depend on the order threads take them in.
std::vector<glm::dvec3> random_start(const FitOptions& options, std::size_t index) {
    Random random(options.seed * 0x9e3779b97f4a7c15ull + index);
    std::vector<glm::dvec3> axes;
    if (options.force_rgb) axes = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    while (axes.size() < options.axes) axes.push_back(random_direction(random));
    return axes;
}

// Projected gradient descent from `axes`: each free axis turns against its gradient by an angle
// proportional to the gradient's size, the largest turning by `step` radians; the step grows by
// 1.25 after an improvement and halves after a failure. Stops after `iterations` steps, when the
// step falls below 1e-9 radians, or at the deadline.
//
// `zeros` (one mask per axis, or empty) pins components at 0: the search runs on what is left.
template <class Evaluate, class Step>
FitResult descend(std::vector<glm::dvec3> axes, std::size_t fixed, std::size_t iterations,
                  const std::optional<Clock::time_point>& deadline, Evaluate evaluate, Step on_step,
                  const std::vector<glm::bvec3>& zeros = {}) {
    auto pin = [&](std::size_t i, glm::dvec3 v) {
        if (!zeros.empty())
            for (int c = 0; c < 3; ++c)
                if (zeros[i][c]) v[c] = 0;
        return v;
    };
    FitResult result;
    Evaluation current = evaluate(axes);
    result.volumes += current.volumes;
    result.computed += current.computed;
    result.failed += current.failed;
    double step = 0.05;
    for (std::size_t it = 0; it < iterations && step > 1e-9; ++it) {
        if (deadline && Clock::now() >= *deadline) {
            result.stopped_early = true;
            break;
        }
        std::vector<glm::dvec3> descent(axes.size(), glm::dvec3(0.0));
        double largest = 0;
        for (std::size_t i = fixed; i < axes.size(); ++i) {
            descent[i] = pin(i, current.gradient[i] - glm::dot(current.gradient[i], axes[i]) * axes[i]);
            largest = std::max(largest, glm::length(descent[i]));
        }
        if (!(largest > 0)) break;
        std::vector<glm::dvec3> trial = axes;
        for (std::size_t i = fixed; i < axes.size(); ++i)
            trial[i] = glm::normalize(pin(i, axes[i] - step * descent[i] / largest));
        Evaluation next = evaluate(trial);
        result.volumes += next.volumes;
        result.computed += next.computed;
        result.failed += next.failed;
        if (next.value < current.value) {
            axes = std::move(trial);
            current = std::move(next);
            step *= 1.25;
        } else {
            step *= 0.5;
        }
        on_step(current.value);
    }
    result.axes = std::move(axes);
    result.score = current.value;
    return result;
}

// Runs `starts` descents and keeps the best (lowest score, then lowest start index).
template <class Descend>
FitResult best_of(std::size_t starts, unsigned threads, Descend descend_from) {
    std::vector<FitResult> results(starts);
    parallel_for(starts, threads, [&](std::size_t s) { results[s] = descend_from(s); });
    FitResult best = results[0];
    std::size_t volumes = 0, computed = 0, failed = 0;
    bool stopped = false;
    for (const FitResult& r : results) {
        volumes += r.volumes;
        computed += r.computed;
        failed += r.failed;
        stopped |= r.stopped_early;
        if (r.score < best.score) best = r;
    }
    best.volumes = volumes;
    best.computed = computed;
    best.failed = failed;
    best.stopped_early = stopped;
    return best;
}

} // namespace

double mean_volume(std::span<const glm::dvec3> axes, const Neighborhoods& neighborhoods, unsigned threads,
                   std::size_t* failed) {
    const Evaluation e = evaluate_neighborhoods(axes, neighborhoods, worker_count(threads));
    if (failed) *failed = e.failed;
    return e.value;
}

FitResult fit_to_sphere(const FitOptions& options, const FitProgress& progress) {
    const auto start_time = Clock::now();
    const std::size_t starts = options.starts ? options.starts : 64;
    const std::size_t iterations = options.iterations ? options.iterations : 400;
    std::mutex mutex;
    std::size_t done = 0;
    double best = std::numeric_limits<double>::infinity();
    FitResult result = best_of(starts, worker_count(options.threads), [&](std::size_t s) {
        FitResult r = descend(random_start(options, s), options.force_rgb ? 3 : 0, iterations, options.deadline,
                              evaluate_sphere, [](double) {});
        std::lock_guard lock(mutex); // a start takes milliseconds: report each, not each step
        best = std::min(best, r.score);
        if (progress) progress(++done, starts, best);
        return r;
    });
    result.seconds = std::chrono::duration<double>(Clock::now() - start_time).count();
    return result;
}

std::vector<double> mean_volumes(std::span<const std::vector<glm::dvec3>> sets, const FrameNeighborhoods& frames,
                                 unsigned threads) {
    std::vector<double> means;
    for (const Evaluation& e : evaluate_frames(sets, frames, worker_count(threads))) means.push_back(e.value);
    return means;
}

FitResult fit_to_neighborhoods(const Neighborhoods& neighborhoods, const FitOptions& options,
                               const FitProgress& progress) {
    return fit_to_neighborhoods(FrameNeighborhoods(neighborhoods), options, progress);
}

FitResult fit_to_neighborhoods(const FrameNeighborhoods& neighborhoods, const FitOptions& options,
                               const FitProgress& progress) {
    const auto start_time = Clock::now();
    const std::size_t starts = options.starts ? options.starts : 4;
    const std::size_t iterations = options.iterations ? options.iterations : 60;
    const unsigned threads = worker_count(options.threads);
    // The starts run one after another, each on every thread: the objective is what costs.
    FitResult result;
    std::size_t done = 0;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t s = 0; s < starts; ++s) {
        // The first start is the best k-DOP around the sphere: a good general shape to refine.
        std::vector<glm::dvec3> from = random_start(options, s);
        if (s == 0) {
            FitOptions sphere = options;
            sphere.starts = 16;
            sphere.iterations = 200;
            sphere.deadline.reset();
            from = fit_to_sphere(sphere).axes;
        }
        FitResult r = descend(
            std::move(from), options.force_rgb ? 3 : 0, iterations, options.deadline,
            [&](std::span<const glm::dvec3> axes) { return evaluate_frames(axes, neighborhoods, threads); },
            [&](double score) {
                best = std::min(best, score);
                if (progress) progress(++done, starts * iterations, best);
            });
        const std::size_t volumes = result.volumes + r.volumes, computed = result.computed + r.computed,
                          failed = result.failed + r.failed;
        const bool stopped =
            r.stopped_early || (s + 1 < starts && options.deadline && Clock::now() >= *options.deadline);
        if (s == 0 || r.score < result.score) result = std::move(r);
        result.volumes = volumes;
        result.computed = computed;
        result.failed = failed;
        result.stopped_early = stopped;
        if (stopped) break;
    }
    result.seconds = std::chrono::duration<double>(Clock::now() - start_time).count();
    return result;
}

double mean_clip_distance(std::span<const glm::dvec3> axes, std::span<const ClipSample> samples, unsigned threads,
                          std::vector<glm::dvec3>* gradient) {
    Evaluation e = evaluate_clip_samples(axes, samples, worker_count(threads));
    if (gradient) *gradient = std::move(e.gradient);
    return e.value;
}

FitResult refine_for_distance(std::vector<glm::dvec3> from, std::span<const ClipSample> samples,
                              const FitOptions& options, const FitProgress& progress) {
    const auto start_time = Clock::now();
    const std::size_t iterations = options.iterations ? options.iterations : 60;
    const unsigned threads = worker_count(options.threads);
    std::size_t done = 0;
    FitResult result = descend(
        std::move(from), options.force_rgb ? 3 : 0, iterations, options.deadline,
        [&](std::span<const glm::dvec3> axes) { return evaluate_clip_samples(axes, samples, threads); },
        [&](double score) {
            if (progress) progress(++done, iterations, score);
        });
    result.seconds = std::chrono::duration<double>(Clock::now() - start_time).count();
    return result;
}

std::size_t nonzero_components(std::span<const glm::dvec3> axes) {
    std::size_t count = 0;
    for (const glm::dvec3& a : axes) count += (a.x != 0) + (a.y != 0) + (a.z != 0);
    return count;
}

std::vector<SparserStep> fit_sparser(const FrameNeighborhoods* neighborhoods, const FitResult& start,
                                     std::size_t max_nonzero, const FitOptions& options, const FitProgress& progress) {
    const unsigned threads = worker_count(options.threads);
    const std::size_t fixed = options.force_rgb ? 3 : 0;
    const std::size_t iterations = options.iterations ? options.iterations : (neighborhoods ? 30 : 200);
    auto evaluate = [&](std::span<const glm::dvec3> axes) {
        return neighborhoods ? evaluate_frames(axes, *neighborhoods, threads) : evaluate_sphere(axes);
    };
    std::vector<glm::dvec3> axes = start.axes;
    std::vector<glm::bvec3> zeros(axes.size(), glm::bvec3(false));
    for (std::size_t i = 0; i < axes.size(); ++i)
        for (int c = 0; c < 3; ++c) zeros[i][c] = axes[i][c] == 0;
    std::vector<SparserStep> steps{{nonzero_components(axes), start.score, axes}};
    const std::size_t total = steps[0].nonzero > max_nonzero ? steps[0].nonzero - max_nonzero : 0;
    while (steps.back().nonzero > max_nonzero) {
        // The smallest component relative to its axis's largest, never the largest itself, nor one
        // whose loss would leave the axis parallel to another (the same slab twice).
        auto parallel_to_another = [&](std::size_t i, const glm::dvec3& a) {
            for (std::size_t j = 0; j < axes.size(); ++j)
                if (j != i && std::abs(glm::dot(a, axes[j])) > std::cos(kParallelAxisAngle)) return true;
            return false;
        };
        std::size_t best_axis = axes.size();
        int best_component = 0;
        double smallest = std::numeric_limits<double>::infinity();
        for (std::size_t i = fixed; i < axes.size(); ++i) {
            const double largest = std::max({std::abs(axes[i].x), std::abs(axes[i].y), std::abs(axes[i].z)});
            int kept_largest = 0;
            for (int c = 0; c < 3; ++c)
                if (std::abs(axes[i][c]) == largest) kept_largest = c;
            for (int c = 0; c < 3; ++c) {
                glm::dvec3 pinned = axes[i];
                pinned[c] = 0;
                if (c != kept_largest && axes[i][c] != 0 && std::abs(axes[i][c]) / largest < smallest &&
                    !parallel_to_another(i, glm::normalize(pinned))) {
                    smallest = std::abs(axes[i][c]) / largest;
                    best_axis = i;
                    best_component = c;
                }
            }
        }
        if (best_axis == axes.size()) break; // one component per axis is all that is left
        zeros[best_axis][best_component] = true;
        axes[best_axis][best_component] = 0;
        axes[best_axis] = glm::normalize(axes[best_axis]);
        FitResult r = descend(
            axes, fixed, iterations, options.deadline, evaluate, [](double) {}, zeros);
        bool collapsed = false; // the refit turned one axis onto another: stop at the step before
        for (std::size_t i = 0; i < axes.size(); ++i) collapsed |= parallel_to_another(i, r.axes[i]);
        if (collapsed) break;
        axes = r.axes;
        steps.push_back({nonzero_components(axes), r.score, axes});
        if (progress) progress(steps.size() - 1, total, r.score);
        if (r.stopped_early) break;
    }
    return steps;
}

} // namespace kdop
