#include "temporal/taa_evaluation.h"

#include "temporal/taa_resolve.h"
#include "temporal/taa_shader.h"

#include <fmt/format.h>

#include <set>

namespace kdop {

TaaEvaluation::TaaEvaluation(const Context& context, const EvaluationOptions& options)
    : context_(&context), options_(options) {
    if (options.cpu_flip) cpu_flip_ = std::make_unique<HdrFlip>(options.ppd);
}

Result<TaaEvaluation> TaaEvaluation::create(const Context& context, std::vector<VariantSpec> specs,
                                            const EvaluationOptions& options) {
    TaaEvaluation evaluation(context, options);
    if (auto ok = evaluation.set_variants(std::move(specs)); !ok) return std::unexpected(ok.error());
    return evaluation;
}

Result<void> TaaEvaluation::set_variants(std::vector<VariantSpec> specs) {
    specs_ = std::move(specs);
    resolve_.reset();
    for (auto& built : shaders_) built.clear();
    // Every variant's resolve is built now, so a shader that does not compile fails before any frame.
    if (!specs_.empty())
        if (auto first = shader(0, false); !first) return std::unexpected(first.error());
    return {};
}

Result<const BoundOwnResolve*> TaaEvaluation::shader(std::size_t v, bool nearer_larger, bool upscale) {
    const bool own = options_.own_resolve.has_value();
    const bool reads_depth = options_.resolve.dilate_motion && nearer_larger;
    auto& built = shaders_[own ? 0 : 2 * int(upscale) + int(reads_depth)];
    if (built.empty()) {
        // All or none: a failed build leaves nothing half-built for the next call to index into.
        ResolveOptions options = options_.resolve;
        options.depth_nearer_larger = reads_depth;
        options.upscale = upscale;
        std::vector<BoundOwnResolve> shaders;
        for (const VariantSpec& spec : specs_) {
            if (own) {
                auto bound = build_bound_resolve(*options_.own_resolve, spec);
                if (!bound) return std::unexpected(bound.error());
                shaders.push_back(std::move(*bound));
                continue;
            }
            auto shader = build_taa_shader(spec, options);
            if (!shader) return std::unexpected(shader.error());
            shaders.push_back({std::move(*shader), {}});
        }
        built = std::move(shaders);
    }
    return &built[v];
}

Result<FlipEvaluator*> TaaEvaluation::flip_evaluator(std::uint32_t width, std::uint32_t height) {
    std::unique_ptr<FlipEvaluator>& evaluator = evaluators_[{width, height}];
    if (evaluator) return evaluator.get();
    if (cpu_flip_) {
        evaluator = cpu_flip_evaluator(*cpu_flip_, options_.exposure);
        return evaluator.get();
    }
    auto created = DeviceFlip::create(*context_, options_.ppd, width, height);
    if (!created) return std::unexpected(created.error());
    DeviceFlip& device = *(device_flips_[{width, height}] = std::move(*created));
    // On a CPU device (lavapipe) the outputs are read back and fed to FLIP from the host: as fast
    // as measuring them where they are, with one frame a variant less held (docs/results.md,
    // "Outputs measured where they are").
    const bool cpu_device = context_->properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    evaluator =
        device_flip_evaluator(device, options_.exposure, cpu_device ? OutputPlacement::host : OutputPlacement::device);
    return evaluator.get();
}

Result<TaaResolve*> TaaEvaluation::resolve(const FrameSource& source, bool nearer_larger) {
    // The last one is kept: a scene's two sequences go through one resolve, each starting its
    // histories afresh. Only one is held, so that sources of other sizes do not add up.
    const bool upscale = source.upscales();
    const ResolveKey key{source.input_width(), source.input_height(), source.width(), source.height(), nearer_larger};
    if (resolve_ && resolve_key_ == key) return resolve_.get();
    resolve_.reset();
    std::vector<const Variant*> shaders;
    std::vector<std::string> names;
    std::vector<const BoundResolve*> roles;
    for (std::size_t v = 0; v < specs_.size(); ++v) {
        auto shader = this->shader(v, nearer_larger, upscale);
        if (!shader) return std::unexpected(shader.error());
        shaders.push_back(&(*shader)->shader->variant());
        names.push_back(variant_name(specs_[v]));
        if (options_.own_resolve) roles.push_back(&(*shader)->roles);
    }
    ResolveOptions options = options_.resolve;
    options.upscale = upscale;
    if (shader_count(source) > specs_.size()) {
        if (!spatial_) {
            auto built = build_spatial_upscale_shader(options);
            if (!built) return std::unexpected(built.error());
            spatial_ = std::move(*built);
        }
        shaders.push_back(&spatial_->variant());
        names.push_back(spatial_upscale_name(options.upscale_filter));
    }
    auto made = TaaResolve::create(*context_, shaders, source.input_width(), source.input_height(), source.width(),
                                   source.height(), options, std::move(names), std::move(roles));
    if (!made) return std::unexpected(made.error());
    resolve_ = std::move(*made);
    resolve_key_ = key;
    return resolve_.get();
}

std::size_t TaaEvaluation::shader_count(const FrameSource& source) const {
    return specs_.size() + std::size_t(options_.spatial_upscale && source.upscales() && !options_.own_resolve);
}

std::size_t TaaEvaluation::frames(const TaaScene&) const {
    return 2 * std::size_t(options_.schedule.warmup + options_.schedule.frames); // its two sequences
}

Result<std::vector<EvaluationRow>> TaaEvaluation::measure(const FrameSource& source, bool nearer_larger,
                                                          const EvaluationObserver& observer) {
    auto flip = flip_evaluator(source.width(), source.height());
    if (!flip) return fail(fmt::format("{}: {}", source.name(), flip.error().message));
    // An upscaled output is compared with the truth at its size, which the input is not.
    if (source.upscales() && !source.has_reference())
        return fail(fmt::format("{}: its frames are {}x{} and its outputs {}x{}, and it has no reference frames at the "
                                "output size to measure them against",
                                source.name(), source.input_width(), source.input_height(), source.width(),
                                source.height()));
    auto resolve = this->resolve(source, nearer_larger);
    if (!resolve) return std::unexpected(resolve.error());
    ShaderOutputObserver output;
    if (observer.output)
        output = [&](std::size_t v, std::size_t index, const Image& image) {
            return observer.output(source.name(), v, index, image);
        };
    FrameObserver on_frame;
    if (observer.frame)
        on_frame = [&] { return observer.frame(observer.source.empty() ? source.name() : observer.source); };
    auto measured = measure_sequence_all(**resolve, source, options_.schedule.warmup, **flip, output, on_frame,
                                         observer.measured, observer.maps, options_.metrics);
    if (!measured) return fail(fmt::format("{}: {}", source.name(), measured.error().message));
    std::vector<EvaluationRow> rows;
    std::set<std::string> noted; // HDR-FLIP's notes, once however many variants meet them
    for (std::size_t v = 0; v < measured->size(); ++v) {
        SequenceMeasurement& m = (*measured)[v];
        EvaluationRow row{v,  source.name(),         std::move(m.means), m.against_reference, m.range, nullptr,
                          {}, std::move(m.per_frame)};
        row.upscale = double(source.width()) / double(source.input_width());
        for (const std::string& note : m.notes)
            if (noted.insert(note).second) row.notes.push_back(note);
        rows.push_back(std::move(row));
    }
    return rows;
}

Result<std::vector<EvaluationRow>> TaaEvaluation::measure(const TaaScene& scene, const EvaluationObserver& observer) {
    // A scene is two sequences, measured as any other: shimmer on the still one, ghosting on the
    // moving one, whose frame scene.trail_frame(schedule) is the scene's trail.
    const std::uint32_t shown = scene.trail_frame(options_.schedule);
    std::vector<std::shared_ptr<const Image>> trails(shader_count(*ghosting_frames(scene, options_.schedule)));
    EvaluationObserver each = observer;
    each.source = scene.name(); // progress counts the scene's frames
    auto still = measure(*shimmer_frames(scene, options_.schedule), false, each);
    if (!still) return std::unexpected(still.error());
    each.output = [&](const std::string& sequence, std::size_t v, std::size_t index, const Image& output) {
        if (index == shown) trails[v] = std::make_shared<const Image>(output);
        return observer.output ? observer.output(sequence, v, index, output) : Result<void>{};
    };
    auto moving = measure(*ghosting_frames(scene, options_.schedule), false, each);
    if (!moving) return std::unexpected(moving.error());
    std::vector<EvaluationRow> rows;
    for (std::size_t v = 0; v < moving->size(); ++v) {
        EvaluationRow row = std::move((*moving)[v]);
        EvaluationRow& shimmer = (*still)[v];
        row.source = scene.name();
        row.means = scene_means(shimmer.means, row.means);
        row.range = ColorRange::ldr;
        row.trail = trails[v] ? trails[v] : std::make_shared<const Image>();
        row.per_frame.insert(row.per_frame.begin(), shimmer.per_frame.begin(), shimmer.per_frame.end());
        row.notes.insert(row.notes.begin(), shimmer.notes.begin(), shimmer.notes.end());
        rows.push_back(std::move(row));
    }
    return rows;
}

Result<std::vector<EvaluationRow>> TaaEvaluation::measure(const SequenceFrames& sequence,
                                                          const EvaluationObserver& observer) {
    // A resolve that does not read depth (kdop's without --dilate-motion, a renderer's without a
    // depth role): its files are not decoded.
    const bool reads_depth =
        options_.own_resolve ? options_.own_resolve->reads_depth() : options_.resolve.dilate_motion;
    const SequenceFrames without_depth = sequence.without_depth();
    const SequenceFrames& source = reads_depth ? sequence : without_depth;
    return measure(source, sequence.sequence().depth_nearer_larger, observer);
}

} // namespace kdop
