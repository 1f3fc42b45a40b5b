#include "optimize/optimize.h"

#include "accuracy/accuracy_inputs.h"
#include "accuracy/sampled_distance.h"
#include "bench/set_cost.h"
#include "core/builtin_sets.h"
#include "core/input_files.h"
#include "core/memory_budget.h"
#include "core/parallel_for.h"
#include "core/write_files.h"
#include "fit/fitted_set.h"
#include "generator/analytic_cost.h"
#include "generator/variant_spec.h"
#include "harness/progress.h"
#include "harness/scratch_directory.h"
#include "images/image_io.h"
#include "reference/cpu_clip.h"
#include "temporal/sequence_ghosting.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <span>

#ifndef KDOP_VERSION
#error "KDOP_VERSION must be defined by the build"
#endif

namespace kdop {
namespace {

using Objective = OptimizeOptions::Objective;

std::vector<ComparedSet> compared_sets(const OptimizeOptions& o, const FrameNeighborhoods* frames,
                                       const std::vector<glm::dvec3>& fitted) {
    std::vector<ComparedSet> sets{{"this set", fitted}};
    for (const std::string& name : builtin_set_names())
        sets.push_back({name, unit_axes(*resolve_axis_set(name))}); // built in: cannot fail
    std::vector<std::vector<glm::dvec3>> axes;
    for (const ComparedSet& set : sets) axes.push_back(set.axes);
    const std::vector<double> scores = frames ? mean_volumes(axes, *frames, o.threads) : std::vector<double>{};
    for (std::size_t i = 0; i < sets.size(); ++i)
        sets[i].score = frames ? scores[i] : KdopPolytope(sets[i].axes).sphere_volume();
    return sets;
}

// Every rank's drawn neighborhoods to every rank, so each holds the whole sample.
void share_sample(const Ranks& ranks, NeighborhoodSampler& sampler, std::size_t frames) {
    std::vector<std::size_t> per_frame;
    for (std::size_t f = 0; f < frames; ++f) per_frame.push_back(sampler.drawn_points(f) * 3);
    std::vector<double> all;
    for (std::size_t f = 0; f < frames; ++f) {
        std::vector<glm::dvec3>& drawn = sampler.drawn(f);
        drawn.resize(per_frame[f] / 3); // another rank's frame: zeros until gathered
        for (const glm::dvec3& p : drawn) all.insert(all.end(), {p.x, p.y, p.z});
    }
    ranks.all_gather(all, per_frame);
    const double* at = all.data();
    for (std::size_t f = 0; f < frames; ++f)
        for (glm::dvec3& p : sampler.drawn(f)) p = glm::dvec3(at[0], at[1], at[2]), at += 3;
}

Result<OptimizeResult> run(const OptimizeOptions& o, const Ranks& ranks, const OptimizeRows& on_row) {
    // Everything the command line decides is checked here, before the fit, which can take minutes.
    const bool by_distance = o.objective == Objective::distance;
    if (by_distance && o.accuracy_samples == 0)
        return usage_fail("--objective distance: the distance is taken on --accuracy-samples pixels; give more than 0");
    if (o.lavapipe_cost && !o.target && !o.target_ghosting && !o.max_nonzero)
        return usage_fail("--lavapipe-cost: counts the rows of --target's, --target-ghosting's or --max-nonzero's "
                          "table; give one of them");
    if (o.force_rgb && o.axes <= 3)
        return usage_fail(fmt::format("--force-rgb fixes 3 axes; --axes {} leaves none to fit", o.axes));
    if (o.max_nonzero && *o.max_nonzero < o.axes)
        return usage_fail(
            fmt::format("--max-nonzero {}: each of the {} axes keeps at least one component", *o.max_nonzero, o.axes));
    const std::string name_option = o.name.empty() ? "--out" : "--name";
    const std::string name = o.name.empty() ? std::filesystem::path(o.out).stem().string() : o.name;
    if (!is_valid_set_name(name))
        return usage_fail(fmt::format("{}: '{}' is not a set name (lowercase letters and digits, single '-' between "
                                      "words); give one with --name",
                                      name_option, name));
    if (is_builtin_set(name))
        return usage_fail(fmt::format("{}: '{}' is the name of a built-in set, which every command would take "
                                      "instead of this file; give another with --name",
                                      name_option, name));
    if (std::error_code ec; std::filesystem::is_directory(o.out, ec))
        return usage_fail(fmt::format("--out {}: is a directory; name the axis-set file to write", o.out));
    if (auto ok = check_output_file(o.out, "--out"); !ok) return usage_fail(ok.error().message);

    // Every neighborhood of every frame, as decoded (--input-space), in the clip's space (--color-map),
    // and with --sample the sample, both from one read of each frame.
    const Neighborhood shape = o.neighborhood;
    FitInputs inputs;
    std::optional<FrameNeighborhoods> neighborhoods, sampled;
    if (o.sphere && ranks.size() > 1)
        return usage_fail(fmt::format("mpirun -np {}: --sphere has no frames to share over ranks (it takes well under "
                                      "a second); run it without mpirun",
                                      ranks.size()));
    // With --target-ghosting, each row's set resolved over the sequences as kdop taa --sequence
    // does, on rank 0 (its figures broadcast): its ghosting and shimmer columns.
    std::unique_ptr<SequenceGhosting> ghosting;
    if (!o.sphere) {
        auto read = fit_inputs(o.input);
        if (!read) return fail(read.error().message);
        inputs = std::move(*read);
        if (auto ok = check_not_an_input(o.out, "--out", inputs.paths); !ok) return std::unexpected(ok.error());
        // Each rank reads and evaluates whole frames: the sums of a frame are the unit whose
        // fixed order makes the result the same for any rank count.
        if (std::size_t(ranks.size()) > inputs.frames.size())
            return usage_fail(fmt::format("mpirun -np {}: {} ranks share {} frame{}; give at most as many ranks as "
                                          "frames",
                                          ranks.size(), ranks.size(), inputs.frames.size(),
                                          inputs.frames.size() == 1 ? "" : "s"));
        // A frame's neighborhoods are gathered whole, held or not: refused up front if the largest
        // frame's would not fit, rather than failing to allocate after minutes of reading.
        std::uint64_t largest = 0;
        for (const FitFrame& frame : inputs.frames)
            largest = std::max(largest, neighborhood_bytes(frame.pixels, shape));
        if (auto ok = check_memory("the neighborhoods of the largest frame", largest); !ok)
            return fail(ok.error().message);
        // Opened before the frames are read, so a sequence the resolve cannot take (--warmup beyond
        // its frames, exit 2) is refused before any work, not after the reading.
        if (o.target_ghosting) {
            Result<void> opened;
            if (ranks.is_root()) {
                ResolveOptions resolve = o.resolve;
                resolve.color_map = o.input.color_map; // the space the set is fitted in is the one it clips in
                auto created = SequenceGhosting::create(o.input.sequences, o.input.input_space, resolve, o.warmup);
                if (created)
                    ghosting = std::move(*created);
                else
                    opened = std::unexpected(created.error());
            }
            if (auto ok = ranks.agree(opened); !ok) return std::unexpected(ok.error());
        }
        // Held between passes while they take at most --memory MB (by default half what is
        // available); the frames beyond are read and gathered again on each pass. With --sample
        // the search passes over the sample alone, and every frame is read again only for the few
        // scores on all of them: by default none is held, so memory is the sample's and one
        // frame's, whatever the frame count.
        const std::uint64_t budget = o.memory ? std::uint64_t(*o.memory * 1024 * 1024)
                                     : o.sample
                                         ? 0
                                         : (available_memory() ? available_memory() / 2 : std::uint64_t(4) << 30);
        std::vector<std::uint64_t> pixels;
        for (const FitFrame& frame : inputs.frames) pixels.push_back(frame.pixels);
        std::optional<NeighborhoodSampler> sampler;
        if (o.sample) sampler.emplace(shape, pixels, *o.sample, o.seed);
        const auto [first, end] = ranks.share(inputs.frames.size());
        FrameShare share{first, end, {}};
        if (ranks.size() > 1)
            share.share = [&ranks](std::span<double> sums, std::size_t per_frame) {
                ranks.all_gather(sums, std::vector<std::size_t>(sums.size() / per_frame, per_frame));
            };
        Progress progress(ranks.size() > 1 ? fmt::format("reading frames on rank 0 of {}", ranks.size())
                                           : std::string("reading frames"),
                          end - first);
        auto gathered =
            FrameNeighborhoods::gather(inputs.frames, shape, budget, share, [&](std::size_t frame, const Image& image) {
                if (sampler) sampler->add(frame, image);
                progress.advance(inputs.frames[frame].label);
            });
        progress.finish();
        // A frame that a rank could not read stops every rank, with its error, before any output.
        if (auto ok = ranks.agree(gathered ? Result<void>{} : std::unexpected(gathered.error())); !ok)
            return fail(ok.error().message);
        neighborhoods = std::move(*gathered);
        if (sampler) {
            if (ranks.size() > 1) share_sample(ranks, *sampler, inputs.frames.size());
            sampled.emplace(sampler->finish());
        }
    }
    // What the search sees: the sample where one is asked for, else every neighborhood.
    const FrameNeighborhoods* fitted_to = sampled ? &*sampled : neighborhoods ? &*neighborhoods : nullptr;

    FitOptions fit{o.axes, o.force_rgb, o.seed, o.threads, o.starts, o.iterations, {}};
    if (o.time_limit > 0)
        fit.deadline =
            std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                   std::chrono::duration<double>(o.time_limit));
    const std::string in_space = o.input.color_map.kind == ColorMap::Kind::linear
                                     ? ""
                                     : fmt::format(", in {} space", to_string(o.input.color_map));
    const std::string objective =
        o.sphere ? "volume of the k-DOP around the unit sphere"
                 : fmt::format("mean k-DOP volume over all {} {} neighborhoods of {}{}", neighborhoods->count(),
                               shape == Neighborhood::n9 ? "3x3" : "plus-shaped", inputs.description, in_space);
    auto fit_axes = [&](std::size_t axes) {
        fit.axes = axes;
        std::unique_ptr<Progress> progress;
        auto on_step = [&](std::size_t done, std::size_t total, double best) {
            if (!progress) progress = std::make_unique<Progress>(fmt::format("fitting {} axes", axes), total);
            if (done <= total) progress->advance(fmt::format("best {:.6g}", best));
        };
        return o.sphere ? fit_to_sphere(fit, on_step) : fit_to_neighborhoods(*fitted_to, fit, on_step);
    };

    // What a set's hardened clip costs: float ops as the generator counts them (analytic_cost.h),
    // and with --lavapipe-cost the instructions per pixel lavapipe runs beyond the gather (callgrind),
    // as the bench counts them.
    std::optional<ScratchDirectory> scratch; // for callgrind's files: only with --lavapipe-cost
    if (o.lavapipe_cost) scratch.emplace("kdop-optimize");
    const bench::CallgrindSetup callgrind{std::filesystem::read_symlink("/proc/self/exe").parent_path() /
                                              "kdop-dispatch-probe",
                                          scratch ? scratch->path : std::filesystem::path(), 256, ""};
    if (o.lavapipe_cost && (callgrind.scratch.empty() || !std::filesystem::exists(callgrind.probe)))
        return fail(fmt::format("--lavapipe-cost: needs {} (built with kdop) and a scratch directory",
                                callgrind.probe.string()));
    // A row's axes as the set the file will hold: what the generator costs and the resolve runs.
    auto as_axis_set = [&](std::span<const glm::dvec3> axes) -> Result<AxisSet> {
        auto text = fitted_set_file({name, "-", {}, o.sphere ? std::nullopt : std::optional(o.input.color_map)}, axes);
        if (!text) return std::unexpected(text.error());
        return parse_axis_set(*text, o.out);
    };
    auto clip_cost = [&](std::span<const glm::dvec3> axes) -> Result<ClipCost> {
        auto set = as_axis_set(axes);
        if (!set) return std::unexpected(set.error());
        ClipCost cost{analytic_min_float_ops(*set, Mode::clip, shape), std::nullopt};
        if (!o.lavapipe_cost) return cost;
        Progress progress("counting lavapipe instructions", 2);
        auto instructions = bench::marginal_clip_instructions(*set, shape, callgrind, progress);
        if (!instructions) return std::unexpected(instructions.error());
        cost.lavapipe_instructions = *instructions;
        return cost;
    };

    // Each row's figures: ghosting, shimmer per sequence.
    auto measure_ghosting = [&](std::span<const glm::dvec3> axes) -> Result<std::vector<double>> {
        std::vector<double> figures(2 * o.input.sequences.size());
        Result<void> measured;
        if (ranks.is_root()) {
            Progress progress("measuring ghosting and shimmer on the sequences", 1);
            auto set = as_axis_set(axes);
            auto m = set ? ghosting->measure(*set, shape) : std::unexpected(set.error());
            if (m)
                for (std::size_t i = 0; i < m->size(); ++i)
                    figures[2 * i] = (*m)[i].mean(kGhosting), figures[2 * i + 1] = (*m)[i].mean(kShimmer);
            else
                measured = std::unexpected(m.error());
        }
        if (auto ok = ranks.agree(measured); !ok) return std::unexpected(ok.error());
        ranks.broadcast(figures);
        return figures;
    };

    // With --target or --target-ghosting, the smallest axis count that reaches it, and the table of
    // every count tried.
    std::vector<std::string> table;
    FitResult result;
    const auto add_row = [&](std::string row) {
        table.push_back(std::move(row));
        if (on_row) on_row(table.back());
    };
    if (o.target || o.target_ghosting) {
        const auto columns = axis_count_columns(o.target_ghosting ? o.input.sequences.size() : 0, o.lavapipe_cost);
        add_row(printed_header(columns));
        bool reached = false;
        double worst = 0; // the largest ghosting over the sequences, with --target-ghosting
        for (std::size_t axes = o.force_rgb ? 4 : 3; axes <= o.axes && !reached; ++axes) {
            result = fit_axes(axes);
            auto cost = clip_cost(result.axes);
            if (!cost) return fail(cost.error().message);
            AxisCountRow row{axes, result.score, {}, {}, *cost};
            if (o.target_ghosting) {
                auto figures = measure_ghosting(result.axes);
                if (!figures) return fail(figures.error().message);
                for (std::size_t i = 0; i < figures->size(); i += 2) {
                    row.ghosting.push_back((*figures)[i]);
                    row.shimmer.push_back((*figures)[i + 1]);
                }
                worst = std::ranges::max(row.ghosting);
            }
            add_row(printed_row(columns, row));
            reached = o.target ? result.score <= *o.target : worst <= *o.target_ghosting;
            if (result.stopped_early) break;
        }
        if (!reached && o.target)
            return fail(fmt::format("--target {:.6g}: no set of up to {} axes reaches it (the last: {:.6g}{})",
                                    *o.target, o.axes, result.score,
                                    result.stopped_early ? ", stopped by --time-limit" : ""));
        if (!reached)
            return fail(fmt::format("--target-ghosting {:.6g}: no set of up to {} axes reaches it (the last "
                                    "ghosts {:.6g}{}); the table above shows the trade",
                                    *o.target_ghosting, o.axes, worst,
                                    result.stopped_early ? ", stopped by --time-limit" : ""));
    } else {
        result = fit_axes(o.axes);
    }
    // With --max-nonzero, components pinned at 0 one by one, and the curve of score against them.
    if (o.max_nonzero) {
        std::unique_ptr<Progress> progress;
        auto steps =
            fit_sparser(fitted_to, result, *o.max_nonzero, fit, [&](std::size_t, std::size_t total, double best) {
                if (!progress) progress = std::make_unique<Progress>("pinning zeros", total);
                progress->advance(fmt::format("score {:.6g}", best));
            });
        if (progress) progress->finish();
        const auto columns = sparser_columns(o.lavapipe_cost);
        add_row(printed_header(columns));
        for (const SparserStep& step : steps) {
            auto cost = clip_cost(step.axes);
            if (!cost) return fail(cost.error().message);
            add_row(printed_row(columns, SparserRow{step.nonzero, step.score, *cost}));
        }
        if (steps.back().nonzero > *o.max_nonzero)
            return fail(fmt::format("--max-nonzero {}: pinning stops at {} nonzero components, where one "
                                    "more zero would turn an axis onto another (the same slab twice); the "
                                    "curve above shows the trade so far",
                                    *o.max_nonzero, steps.back().nonzero));
        result.axes = steps.back().axes;
        result.score = steps.back().score;
    }
    // The distance's pixels: for --objective distance, then for the distance every set is reported
    // at. Read after the neighborhoods are freed (so the peak stays within the memory held)
    // unless the distance objective needs both.
    std::vector<ClipSample> samples;
    auto read_samples = [&]() -> Result<void> {
        auto read = fit_distance_samples(o.input, inputs, shape, o.accuracy_samples, o.seed);
        if (auto ok = ranks.agree(read ? Result<void>{} : std::unexpected(read.error())); !ok) return ok;
        samples = std::move(*read);
        return {};
    };
    // --objective distance: the volume fit, refined on the distance (the clip's own, in double).
    std::string refined_line;
    double refined_score = NAN;
    if (by_distance) {
        if (auto ok = read_samples(); !ok) return fail(ok.error().message);
        // From the volume fit and from every built-in set of as many axes (none with --force-rgb,
        // whose first axes are fixed): the distance is not smooth, a descent ends at the first
        // kink it cannot pass, and a built-in set can be a better place to start (on desert5 the
        // volume fit descends to 0.0191 while dop16-grass starts at 0.0182).
        std::vector<std::pair<std::string, std::vector<glm::dvec3>>> starts{{"the volume fit", result.axes}};
        if (!o.force_rgb)
            for (const std::string& set : builtin_set_names())
                if (auto axes = unit_axes(*resolve_axis_set(set)); axes.size() == result.axes.size())
                    starts.emplace_back(set, std::move(axes));
        Progress progress("descending on the distance", starts.size());
        FitResult best;
        std::string from_name;
        double from = NAN;
        for (const auto& [start_name, axes] : starts) {
            const double start = mean_clip_distance(axes, samples, o.threads);
            FitResult refined = refine_for_distance(axes, samples, fit);
            if (from_name.empty() || refined.score < best.score)
                best = std::move(refined), from_name = start_name, from = start;
            progress.advance(fmt::format("from {}: {:.6g}", start_name, best.score));
        }
        progress.finish();
        refined_line =
            fmt::format("descended on the distance to the ideal clip from {} start{}; the best, from {}: {:.6g} to "
                        "{:.6g} ({:+.2f}%)",
                        starts.size(), starts.size() == 1 ? "" : "s", from_name, from, best.score,
                        100.0 * (best.score / from - 1.0));
        refined_score = best.score;
        result.axes = std::move(best.axes);
        result.stopped_early |= best.stopped_early;
    }
    // Every set's volume on every neighborhood, in one more pass over the frames: a sampled fit's
    // worth on the data beside what the search saw, a refined fit's volume, the built-in sets'.
    std::vector<ComparedSet> sets = compared_sets(o, neighborhoods ? &*neighborhoods : nullptr, result.axes);
    const double sample_score = result.score;
    result.score = sets[0].score;
    std::string sample_line; // empty without --sample
    if (o.sample)
        sample_line = fmt::format("fitted to {} of the {} neighborhoods, sampled by luminance (seed {}): {:.6g} on "
                                  "the sample, {:.6g} on all ({:+.2f}%)",
                                  sampled->count(), neighborhoods->count(), o.seed, sample_score, result.score,
                                  100.0 * (result.score / sample_score - 1.0));
    const std::size_t frames = neighborhoods ? neighborhoods->own_frames() : 0,
                      held = neighborhoods ? neighborhoods->held_frames() : 0;
    neighborhoods.reset();
    sampled.reset();
    if (!by_distance && !o.sphere && o.accuracy_samples > 0)
        if (auto ok = read_samples(); !ok) return fail(ok.error().message);
    const std::string distance_measure =
        samples.empty()
            ? ""
            : fmt::format("mean distance to the ideal clip (kdop accuracy's measure, CPU reference) over {} "
                          "sampled pixels: up to {} of each {} under each of its 3 ghosting histories, "
                          "seed {}{}",
                          samples.size(), o.accuracy_samples,
                          o.input.sequences.empty() ? "image" : "image and sequence (spread over its frames)", o.seed,
                          in_space);
    if (!samples.empty()) {
        std::vector<std::vector<glm::dvec3>> axes;
        for (const ComparedSet& set : sets) axes.push_back(set.axes);
        const SampledDistances distances = sampled_ideal_distances(samples, axes);
        for (std::size_t i = 0; i < sets.size(); ++i) sets[i].distance = distances.mean[i];
    }
    // A built-in set of no more axes that lands closer to the ideal clip than the fit: a tighter
    // volume is not always a nearer clip (an 8-axis fit to colobot's desert5 has a 2.2x smaller
    // volume than dop16-grass and a 9% larger distance), and shipping the fit would then be worse.
    const ComparedSet* closer = nullptr;
    for (const ComparedSet& set : std::span(sets).subspan(1))
        if (set.axes.size() <= sets[0].axes.size() && set.distance < sets[0].distance &&
            (!closer || set.distance < closer->distance))
            closer = &set;
    std::string closer_warning;
    if (closer)
        closer_warning = fmt::format(
            "the built-in {} ({} axes) lands closer to the ideal clip than this set on these images ({:.6g} "
            "against {:.6g}); consider it instead ({})",
            closer->name, closer->axes.size(), closer->distance, sets[0].distance,
            closer->score < sets[0].score ? "its volume is smaller too: the search stopped short of it, and more "
                                            "--starts or --iterations may find a better set"
                                          : "this set's volume is smaller: a tighter k-DOP is not always a nearer "
                                            "clip");

    // The file: what was fitted to and how, and the objective next to the built-in sets'.
    const std::string fitted_objective =
        by_distance ? fmt::format("{}, then the mean distance to the ideal clip on {} sampled pixels", objective,
                                  samples.size())
                    : objective;
    const double fitted_score = by_distance ? refined_score : result.score;
    FittedSetText text{name,
                       fmt::format("fitted by kdop {} optimize (seed {}): {} = {:.6g}", KDOP_VERSION, o.seed,
                                   fitted_objective, fitted_score),
                       {},
                       // An image fit is a fit in one space; a sphere fit, to no colors, is for any.
                       o.sphere ? std::nullopt : std::optional(o.input.color_map)};
    text.comments.push_back(fmt::format("Fitted by `kdop optimize` {}: {} axes{}, seed {}, {} starts x {} steps{}.",
                                        KDOP_VERSION, result.axes.size(), o.force_rgb ? " (R, G, B forced)" : "",
                                        o.seed, o.starts ? fmt::format("{}", o.starts) : "default",
                                        o.iterations ? fmt::format("{}", o.iterations) : "default",
                                        result.stopped_early ? ", stopped early by --time-limit" : ""));
    text.comments.push_back(fmt::format("Objective: {}.", fitted_objective));
    if (o.sample) text.comments.push_back(fmt::format("Sampled: {}.", sample_line));
    if (by_distance) text.comments.push_back(fmt::format("Refined: {}.", refined_line));
    if (o.target) text.comments.push_back(fmt::format("The fewest axes that reach --target {:.6g}:", *o.target));
    if (o.target_ghosting)
        text.comments.push_back(fmt::format("The fewest axes whose ghosting reaches --target-ghosting {:.6g} on {} "
                                            "(kdop taa --sequence's measure, warmup {}, LDR- or HDR-FLIP as each "
                                            "sequence says):",
                                            *o.target_ghosting, fmt::join(o.input.sequences, ", "), o.warmup));
    if (o.max_nonzero)
        text.comments.push_back(fmt::format("Components pinned at 0 one by one, to at most {}:", *o.max_nonzero));
    for (const std::string& row : table) text.comments.push_back("  " + row);
    if (!distance_measure.empty()) text.comments.push_back(fmt::format("Distance: {}.", distance_measure));
    text.comments.push_back(fmt::format("Volume{} of this set and the built-in sets (x this set's):",
                                        distance_measure.empty() ? "" : ", then distance,"));
    const auto compared = compared_set_columns(sets[0], !distance_measure.empty());
    for (const ComparedSet& set : sets) text.comments.push_back("  " + printed_row(compared, set));
    if (closer) text.comments.push_back(fmt::format("Warning: {}.", closer_warning));
    auto file = fitted_set_file(text, result.axes);
    if (!file) return fail(file.error().message);
    // The same file on every rank: rank 0 writes it.
    if (ranks.is_root())
        if (o.write_out)
            if (auto ok = write_files_atomically({{o.out, *file}}); !ok) return fail(ok.error().message);

    OptimizeResult out;
    out.file = std::move(*file);
    out.fit = std::move(result);
    out.fitted_objective = fitted_objective;
    out.fitted_score = fitted_score;
    out.sample_line = sample_line;
    out.refined_line = refined_line;
    out.distance_measure = distance_measure;
    out.sets = std::move(sets);
    out.closer_warning = closer_warning;
    out.own_frames = frames;
    out.held_frames = held;
    out.frames = inputs.frames.size();
    return out;
}

} // namespace

Result<OptimizeResult> optimize(const OptimizeOptions& options, const Ranks& ranks, const OptimizeRows& on_row) {
    // One process's threads share its cores with the other ranks on the machine.
    OptimizeOptions o = options;
    if (const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE"); local && o.threads == 0)
        o.threads = std::max(1u, core_count() / unsigned(std::max(1, std::atoi(local))));
    try {
        return run(o, ranks, on_row);
    } catch (const FitInputError& e) {
        if (ranks.size() > 1) ranks.abort(e.what()); // the others wait in a collective
        return fail(e.what());
    }
}

} // namespace kdop
