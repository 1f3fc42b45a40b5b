#include "optimize/fit_compare.h"

#include "accuracy/sampled_distance.h"
#include "core/builtin_sets.h"
#include "fit/fitted_set.h"
#include "reference/cpu_clip.h"

#include <fmt/format.h>

#include <span>

#ifndef KDOP_VERSION
#error "KDOP_VERSION must be defined by the build"
#endif

namespace kdop {

std::vector<ComparedSet> compared_sets(const FrameNeighborhoods* frames, const std::vector<glm::dvec3>& fitted,
                                       unsigned threads) {
    std::vector<ComparedSet> sets{{"this set", fitted}};
    for (const std::string& name : builtin_set_names())
        sets.push_back({name, unit_axes(*resolve_axis_set(name))}); // built in: cannot fail
    std::vector<std::vector<glm::dvec3>> axes;
    for (const ComparedSet& set : sets) axes.push_back(set.axes);
    const std::vector<double> scores = frames ? mean_volumes(axes, *frames, threads) : std::vector<double>{};
    for (std::size_t i = 0; i < sets.size(); ++i)
        sets[i].score = frames ? scores[i] : KdopPolytope(sets[i].axes).sphere_volume();
    return sets;
}

std::string sample_line(const FitData& data, std::uint64_t seed, double on_sample, double on_all) {
    return fmt::format("fitted to {} of the {} neighborhoods, sampled by luminance (seed {}): {:.6g} on the sample, "
                       "{:.6g} on all ({:+.2f}%)",
                       data.sampled->count(), data.neighborhoods->count(), seed, on_sample, on_all,
                       100.0 * (on_all / on_sample - 1.0));
}

Result<std::vector<ClipSample>> read_distance_samples(const OptimizeOptions& o, const FitData& data,
                                                      const Ranks& ranks) {
    auto read = fit_distance_samples(o.input, data.inputs, o.neighborhood, o.accuracy_samples, o.seed);
    if (auto ok = ranks.agree(read ? Result<void>{} : std::unexpected(read.error())); !ok)
        return std::unexpected(ok.error());
    return read;
}

std::string distance_measure(const OptimizeOptions& o, std::size_t samples) {
    if (samples == 0) return "";
    const std::string in_space = o.input.color_map.kind == ColorMap::Kind::linear
                                     ? ""
                                     : fmt::format(", in {} space", to_string(o.input.color_map));
    return fmt::format("mean distance to the ideal clip (kdop accuracy's measure, CPU reference) over {} sampled "
                       "pixels: up to {} of each {} under each of its 3 ghosting histories, seed {}{}",
                       samples, o.accuracy_samples,
                       o.input.sequences.empty() ? "image" : "image and sequence (spread over its frames)", o.seed,
                       in_space);
}

void add_distances(std::vector<ComparedSet>& sets, const std::vector<ClipSample>& samples) {
    if (samples.empty()) return;
    std::vector<std::vector<glm::dvec3>> axes;
    for (const ComparedSet& set : sets) axes.push_back(set.axes);
    const SampledDistances distances = sampled_ideal_distances(samples, axes);
    for (std::size_t i = 0; i < sets.size(); ++i) sets[i].distance = distances.mean[i];
}

std::string closer_warning(const std::vector<ComparedSet>& sets) {
    // A tighter volume is not always a nearer clip (an 8-axis fit to colobot's desert5 has a 2.2x
    // smaller volume than dop16-grass and a 9% larger distance), and shipping the fit would then be worse.
    const ComparedSet* closer = nullptr;
    for (const ComparedSet& set : std::span(sets).subspan(1))
        if (set.axes.size() <= sets[0].axes.size() && set.distance < sets[0].distance &&
            (!closer || set.distance < closer->distance))
            closer = &set;
    if (!closer) return "";
    return fmt::format("the built-in {} ({} axes) lands closer to the ideal clip than this set on these images "
                       "({:.6g} against {:.6g}); consider it instead ({})",
                       closer->name, closer->axes.size(), closer->distance, sets[0].distance,
                       closer->score < sets[0].score
                           ? "its volume is smaller too: the search stopped short of it, and more --starts or "
                             "--iterations may find a better set"
                           : "this set's volume is smaller: a tighter k-DOP is not always a nearer clip");
}

Result<std::string> fitted_set_text(const FitRecord& r, std::span<const glm::dvec3> axes) {
    FittedSetText text{
        r.name,
        fmt::format("fitted by kdop {} optimize (seed {}): {} = {:.6g}", KDOP_VERSION, r.seed, r.objective, r.score),
        {},
        r.color_map};
    text.comments.push_back(fmt::format("Fitted by `kdop optimize` {}: {} axes{}, seed {}, {} starts x {} steps{}.",
                                        KDOP_VERSION, axes.size(), r.force_rgb ? " (R, G, B forced)" : "", r.seed,
                                        r.starts ? fmt::format("{}", r.starts) : "default",
                                        r.iterations ? fmt::format("{}", r.iterations) : "default",
                                        r.stopped_early ? ", stopped early by --time-limit" : ""));
    text.comments.push_back(fmt::format("Objective: {}.", r.objective));
    text.comments.insert(text.comments.end(), r.notes.begin(), r.notes.end());
    if (!r.distance_measure.empty()) text.comments.push_back(fmt::format("Distance: {}.", r.distance_measure));
    text.comments.push_back(fmt::format("Volume{} of this set and the built-in sets (x this set's):",
                                        r.distance_measure.empty() ? "" : ", then distance,"));
    const auto compared = compared_set_columns(r.sets[0], !r.distance_measure.empty());
    for (const ComparedSet& set : r.sets) text.comments.push_back("  " + printed_row(compared, set));
    if (!r.closer_warning.empty()) text.comments.push_back(fmt::format("Warning: {}.", r.closer_warning));
    return fitted_set_file(text, axes);
}

} // namespace kdop
