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
    for (auto& built : shaders_) built.clear();
    // Every variant's resolve is built now, so a shader that does not compile fails before any frame.
    if (!specs_.empty())
        if (auto first = shader(0, false); !first) return std::unexpected(first.error());
    return {};
}

Result<const Variant*> TaaEvaluation::shader(std::size_t v, bool nearer_larger) {
    const bool reads_depth = options_.resolve.dilate_motion && nearer_larger;
    auto& built = shaders_[reads_depth ? 1 : 0];
    if (built.empty()) {
        // All or none: a failed build leaves nothing half-built for the next call to index into.
        ResolveOptions options = options_.resolve;
        options.depth_nearer_larger = reads_depth;
        std::vector<std::unique_ptr<RunnableVariant>> shaders;
        for (const VariantSpec& spec : specs_) {
            auto shader = build_taa_shader(spec, options);
            if (!shader) return std::unexpected(shader.error());
            shaders.push_back(std::move(*shader));
        }
        built = std::move(shaders);
    }
    return &built[v]->variant();
}

Result<FlipMean> TaaEvaluation::flip_mean(std::uint32_t width, std::uint32_t height) {
    if (cpu_flip_) return cpu_flip_mean(*cpu_flip_, options_.exposure);
    std::unique_ptr<DeviceFlip>& device = device_flips_[{width, height}];
    if (!device) {
        auto created = DeviceFlip::create(*context_, options_.ppd, width, height);
        if (!created) return std::unexpected(created.error());
        device = std::move(*created);
    }
    FlipMean mean = device_flip_mean(*device, options_.exposure);
    // On a CPU device (lavapipe) the outputs are read back and fed to FLIP from the host: measured
    // where they are (DeviceFlip::load), a 1920x1080 run of 12 variants took as long (1.02x) and
    // held one more frame per variant (+380 MiB), since the device's memory is the host's and every
    // copy the CPU's either way (docs/results.md, "Outputs measured where they are").
    if (context_->properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) mean.device = nullptr;
    return mean;
}

Result<std::unique_ptr<TaaResolve>> TaaEvaluation::resolve(std::uint32_t width, std::uint32_t height,
                                                           bool nearer_larger) {
    std::vector<const Variant*> shaders;
    std::vector<std::string> names;
    for (std::size_t v = 0; v < specs_.size(); ++v) {
        auto shader = this->shader(v, nearer_larger);
        if (!shader) return std::unexpected(shader.error());
        shaders.push_back(*shader);
        names.push_back(variant_name(specs_[v]));
    }
    return TaaResolve::create(*context_, shaders, width, height, options_.resolve, std::move(names));
}

std::size_t TaaEvaluation::frames(const TaaScene&) const {
    return 2 * std::size_t(options_.schedule.warmup + options_.schedule.frames); // its two sequences
}

Result<std::vector<EvaluationRow>> TaaEvaluation::measure(const TaaScene& scene, const EvaluationObserver& observer) {
    auto mean = flip_mean(scene.width(), scene.height());
    if (!mean) return fail(fmt::format("{}: {}", scene.name(), mean.error().message));
    auto resolve = this->resolve(scene.width(), scene.height(), false);
    if (!resolve) return std::unexpected(resolve.error());
    auto on_frame = [&] {
        if (observer.frame) observer.frame(scene.name());
    };
    auto measured = measure_scene_all(**resolve, scene, options_.schedule, *mean, observer.output, on_frame,
                                      observer.measured, observer.maps);
    if (!measured) return fail(fmt::format("{}: {}", scene.name(), measured.error().message));
    std::vector<EvaluationRow> rows;
    for (std::size_t v = 0; v < specs_.size(); ++v) {
        TaaMeasurement& m = (*measured)[v];
        rows.push_back({v,
                        scene.name(),
                        m.shimmer,
                        m.ghosting,
                        m.against_reference,
                        ColorRange::ldr,
                        std::make_shared<const Image>(std::move(m.trail)),
                        {},
                        std::move(m.per_frame)});
    }
    return rows;
}

Result<std::vector<EvaluationRow>> TaaEvaluation::measure(const SequenceFrames& sequence,
                                                          const EvaluationObserver& observer) {
    auto mean = flip_mean(sequence.width(), sequence.height());
    if (!mean) return fail(fmt::format("{}: {}", sequence.name(), mean.error().message));
    auto resolve = this->resolve(sequence.width(), sequence.height(), sequence.sequence().depth_nearer_larger);
    if (!resolve) return std::unexpected(resolve.error());
    ShaderOutputObserver output;
    if (observer.output)
        output = [&](std::size_t v, std::size_t index, const Image& image) {
            return observer.output(sequence.name(), v, index, image);
        };
    auto on_frame = [&] {
        if (observer.frame) observer.frame(sequence.name());
    };
    // A resolve that does not dilate motion never reads depth: its files are not decoded.
    const SequenceFrames without_depth = sequence.without_depth();
    const SequenceFrames& source = options_.resolve.dilate_motion ? sequence : without_depth;
    auto measured = measure_sequence_all(**resolve, source, options_.schedule.warmup, *mean, output, on_frame,
                                         observer.measured, observer.maps);
    if (!measured) return fail(fmt::format("{}: {}", sequence.name(), measured.error().message));
    std::vector<EvaluationRow> rows;
    std::set<std::string> noted; // HDR-FLIP's notes, once however many variants meet them
    for (std::size_t v = 0; v < specs_.size(); ++v) {
        SequenceMeasurement& m = (*measured)[v];
        EvaluationRow row{v,  sequence.name(),       m.shimmer, m.ghosting, m.against_reference, m.range, nullptr,
                          {}, std::move(m.per_frame)};
        for (const std::string& note : m.notes)
            if (noted.insert(note).second) row.notes.push_back(note);
        rows.push_back(std::move(row));
    }
    return rows;
}

} // namespace kdop
