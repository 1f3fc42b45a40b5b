#include "accuracy_run.h"

#include "cpu_clip.h"
#include "ideal_clip.h"
#include "kernel.h"
#include "rectify_pass.h"
#include "runnable_variant.h"
#include "spirv_cost.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <map>
#include <memory>
#include <set>

namespace kdop {
namespace {

std::set<Neighborhood> shapes_of(const std::vector<VariantSpec>& specs) {
    std::set<Neighborhood> shapes;
    for (const VariantSpec& s : specs) shapes.insert(s.neighborhood);
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
    return pairs * (shapes_of(options.specs).size() + 1);
}

Result<AccuracyRun> run_accuracy(const Context& context, const AccuracyOptions& options,
                                 const std::vector<AccuracyPair>& pairs, const AccuracyProgress& progress) {
    for (const VariantSpec& spec : options.specs)
        if (spec.mode != Mode::clip && spec.mode != Mode::varclip)
            return fail(fmt::format("{}: only clip variants have an accuracy", variant_name(spec)));
    auto built = build_variants(options.specs);
    if (!built) return std::unexpected(built.error());
    std::vector<std::unique_ptr<RunnableVariant>> variants;
    std::vector<std::unique_ptr<Kernel>> kernels;
    std::vector<AccuracyRow> described; // what each variant's rows say of the variant itself
    for (BuiltVariant& b : *built) {
        AccuracyRow& row = described.emplace_back();
        row.variant = b.name;
        row.axis_set = b.spec.set.name;
        row.mode = to_string(b.spec.mode);
        row.neighborhood = to_string(b.spec.neighborhood);
        row.k = static_cast<unsigned>(2 * b.spec.set.axes.size());
        row.rgb_axes = contains_rgb_axes(b.spec.set);
        row.float_ops = count_float_ops(b.spirv).total();
        variants.push_back(std::make_unique<RunnableVariant>(std::move(b)));
        auto kernel = Kernel::create(context, variants.back()->variant());
        if (!kernel) return std::unexpected(kernel.error());
        kernels.push_back(std::move(*kernel));
    }

    AccuracyRun run{{}, context.device_name(), context.driver_info()};
    for (const AccuracyPair& pair : pairs) {
        std::map<Neighborhood, std::vector<double>> ideal;
        std::map<Neighborhood, std::vector<SolidPixel>> sample;
        for (Neighborhood shape : shapes_of(options.specs)) {
            if (progress) progress(fmt::format("{}: ideal clip {}", pair.name, to_string(shape)));
            auto exits = ideal_exits(pair.current, pair.history, shape);
            if (!exits) return fail(fmt::format("{}: {}", pair.name, exits.error().message));
            ideal[shape] = std::move(*exits);
            auto solid = sample_solid_pixels(pair.current, shape, options.volume_samples, options.seed);
            if (!solid) return fail(fmt::format("{}: {}", pair.name, solid.error().message));
            sample[shape] = std::move(*solid);
        }

        if (progress) progress(fmt::format("{}: {} variants", pair.name, variants.size()));
        auto pass = RectifyPass::create(context, pair.current.width, pair.current.height, TextureFormat::rgba32f);
        if (!pass) return std::unexpected(pass.error());
        if (auto ok = (*pass)->upload(pair.current, pair.history); !ok) return std::unexpected(ok.error());
        const std::size_t first_row = run.rows.size();
        std::vector<Distances> distances;
        for (std::size_t v = 0; v < variants.size(); ++v) {
            const VariantSpec& spec = variants[v]->built().spec;
            if (auto ok = (*pass)->dispatch(*kernels[v], options.gamma); !ok) return std::unexpected(ok.error());
            auto output = (*pass)->download();
            if (!output) return std::unexpected(output.error());
            const Image reference =
                reference_rectify(spec.set, spec.mode, spec.neighborhood, pair.current, pair.history, options.gamma);
            const std::vector<double>& exits = ideal[spec.neighborhood];
            Distances& d = distances.emplace_back(Distances{ideal_distances(pair.current, pair.history, exits, *output),
                                                            ideal_distances(pair.current, pair.history, exits, reference)});

            AccuracyRow row = described[v];
            row.family = pair.family;
            row.image = pair.name;
            row.gpu = measure_accuracy(pair.current, pair.history, exits, *output, d.gpu);
            row.reference = measure_accuracy(pair.current, pair.history, exits, reference, d.reference);
            row.gpu_reference_max = largest_difference(pair.current, *output, reference);
            auto volume = volume_ratio(pair.current, sample[spec.neighborhood], spec.set, spec.mode, spec.neighborhood,
                                       options.gamma);
            if (!volume) return fail(fmt::format("{}: {}", pair.name, volume.error().message));
            row.volume = *volume;
            run.rows.push_back(std::move(row));
        }
        // Each variant against the RGB AABB of its mode and neighborhood, when that was selected.
        for (std::size_t v = 0; v < variants.size(); ++v)
            for (std::size_t a = 0; a < variants.size(); ++a) {
                const VariantSpec &spec = variants[v]->built().spec, &aabb = variants[a]->built().spec;
                if (aabb.set.name != "aabb" || aabb.mode != spec.mode || aabb.neighborhood != spec.neighborhood) continue;
                AccuracyRow& row = run.rows[first_row + v];
                row.vs_aabb = compare_distances(distances[v].gpu, distances[a].gpu);
                row.reference_vs_aabb = compare_distances(distances[v].reference, distances[a].reference);
            }
    }
    return run;
}

} // namespace kdop
