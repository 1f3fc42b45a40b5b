#include "accuracy/accuracy_run.h"

#include "accuracy/ideal_clip.h"
#include "core/builtin_sets.h"
#include "generator/spirv_cost.h"
#include "reference/cpu_clip.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <map>
#include <set>

namespace kdop {
namespace {

std::set<Neighborhood> shapes_of(const std::vector<VariantKey>& keys) {
    std::set<Neighborhood> shapes;
    for (const VariantKey& k : keys) shapes.insert(k.neighborhood);
    return shapes;
}

// The largest |a - b| / S over the pixels.
double largest_difference(const Image& current, const Image& a, const Image& b) {
    double largest = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        largest = std::max(largest, glm::distance(glm::dvec3(a.pixels[i]), glm::dvec3(b.pixels[i])) /
                                        pixel_magnitude(current.pixels[i]));
    return largest;
}

bool contains_rgb_axes(const AxisSet& set) {
    const std::vector<glm::dvec3> axes = unit_axes(set);
    const auto has = [&](glm::dvec3 axis) { return std::find(axes.begin(), axes.end(), axis) != axes.end(); };
    return has({1, 0, 0}) && has({0, 1, 0}) && has({0, 0, 1});
}

// What each variant's output was on one pair, kept until the AABB comparison.
struct Distances {
    std::vector<double> gpu, reference;
};

} // namespace

std::size_t accuracy_steps(const AccuracyOptions& options, std::size_t pairs) {
    return pairs * (shapes_of(options.variants).size() + 1);
}

Result<AccuracyRun> run_accuracy(DeviceRunner& runner, VariantCatalog& catalog, const AccuracyOptions& options,
                                 const std::vector<AccuracyPair>& pairs, Progress* progress) {
    for (const VariantKey& key : options.variants)
        if (!key.is_clip()) return fail(fmt::format("{}: only clip variants have an accuracy", key.name()));
    auto variants = catalog.find_all(options.variants, "--sets");
    if (!variants) return std::unexpected(variants.error());
    std::vector<VariantSpec> specs;     // what the reference and the volumes need of each variant
    std::vector<AccuracyRow> described; // what each variant's rows say of the variant itself
    for (std::size_t v = 0; v < options.variants.size(); ++v) {
        const VariantKey& key = options.variants[v];
        auto spec = catalog.spec(key, "--sets");
        if (!spec) return std::unexpected(spec.error());
        specs.push_back(std::move(*spec));
        AccuracyRow& row = described.emplace_back();
        row.key = key;
        row.k = static_cast<unsigned>(2 * specs.back().set.axes.size());
        row.rgb_axes = contains_rgb_axes(specs.back().set);
        row.float_ops = count_float_ops({(*variants)[v]->spirv, (*variants)[v]->spirv_word_count}).total();
    }

    AccuracyRun run;
    for (const AccuracyPair& pair : pairs) {
        std::map<Neighborhood, std::vector<double>> ideal;
        std::map<Neighborhood, std::vector<SolidPixel>> sample;
        for (Neighborhood shape : shapes_of(options.variants)) {
            auto exits = ideal_exits(pair.current, pair.history, shape);
            if (!exits) return fail(fmt::format("{}: {}", pair.name, exits.error().message));
            ideal[shape] = std::move(*exits);
            auto solid = sample_solid_pixels(pair.current, shape, options.volume_samples, options.seed);
            if (!solid) return fail(fmt::format("{}: {}", pair.name, solid.error().message));
            sample[shape] = std::move(*solid);
            if (progress) progress->advance(fmt::format("{}: ideal clip {}", pair.name, to_string(shape)));
        }

        const std::size_t first_row = run.rows.size();
        std::vector<Distances> distances;
        auto ran = runner.run(pair.current, pair.history, TextureFormat::rgba32f, *variants, options.gamma,
                              [&](std::size_t v, const Image& output) -> Result<void> {
                                  const VariantSpec& spec = specs[v];
                                  const Image reference = reference_rectify(spec.set, spec.mode, spec.neighborhood,
                                                                            pair.current, pair.history, options.gamma);
                                  const std::vector<double>& exits = ideal[spec.neighborhood];
                                  Distances& d = distances.emplace_back(
                                      Distances{ideal_distances(pair.current, pair.history, exits, output),
                                                ideal_distances(pair.current, pair.history, exits, reference)});
                                  AccuracyRow row = described[v];
                                  row.family = pair.family;
                                  row.image = pair.name;
                                  row.gpu = measure_accuracy(pair.current, pair.history, exits, output, d.gpu);
                                  row.reference =
                                      measure_accuracy(pair.current, pair.history, exits, reference, d.reference);
                                  row.gpu_reference_max = largest_difference(pair.current, output, reference);
                                  auto volume = volume_ratio(pair.current, sample[spec.neighborhood], spec.set,
                                                             spec.mode, spec.neighborhood, options.gamma);
                                  if (!volume) return fail(fmt::format("{}: {}", pair.name, volume.error().message));
                                  row.volume = *volume;
                                  run.rows.push_back(std::move(row));
                                  return {};
                              });
        if (!ran) return std::unexpected(ran.error());
        if (progress) progress->advance(fmt::format("{}: {} variants", pair.name, specs.size()));
        // Each variant against the RGB AABB of its mode and neighborhood, when that was selected.
        for (std::size_t v = 0; v < specs.size(); ++v)
            for (std::size_t a = 0; a < specs.size(); ++a) {
                if (options.variants[a] != options.variants[v].with_set(kRgbBox)) continue;
                AccuracyRow& row = run.rows[first_row + v];
                row.vs_aabb = compare_distances(distances[v].gpu, distances[a].gpu);
                row.reference_vs_aabb = compare_distances(distances[v].reference, distances[a].reference);
            }
    }
    return run;
}

} // namespace kdop
