#include "sequence_ghosting.h"

#include "flip.h"
#include "taa_resolve.h"
#include "taa_shader.h"
#include "variant_spec.h"

#include <fmt/format.h>

namespace kdop::cli {

Result<std::unique_ptr<SequenceGhosting>> SequenceGhosting::create(const std::vector<std::string>& dirs,
                                                                   InputSpace space, const ResolveOptions& options,
                                                                   std::uint32_t warmup) {
    auto out = std::unique_ptr<SequenceGhosting>(new SequenceGhosting);
    out->options_ = options;
    out->warmup_ = warmup;
    auto context = Context::create({});
    if (!context) return std::unexpected(context.error());
    out->context_ = std::move(*context);
    for (const std::string& dir : dirs) {
        auto sequence = read_resolvable_sequence(dir, warmup, options);
        if (!sequence) return std::unexpected(sequence.error());
        if (auto ok = check_measurable(*out->context_, sequence->width, sequence->height, true); !ok)
            return fail(fmt::format("--sequence {}: {}", dir, ok.error().message));
        out->sequences_.emplace_back(std::move(*sequence), space);
    }
    return out;
}

Result<std::vector<SequenceMeasurement>> SequenceGhosting::measure(const AxisSet& set, Neighborhood shape) {
    VariantSpec spec;
    spec.set = set;
    spec.mode = Mode::clip;
    spec.neighborhood = shape;
    std::vector<SequenceMeasurement> measured;
    for (const SequenceFrames& sequence : sequences_) {
        ResolveOptions options = options_;
        options.depth_nearer_larger = options.dilate_motion && sequence.sequence().depth_nearer_larger;
        auto shader = build_taa_shader(spec, options);
        if (!shader) return std::unexpected(shader.error());
        std::unique_ptr<DeviceFlip>& flip = flips_[{sequence.width(), sequence.height()}];
        if (!flip) {
            auto created = DeviceFlip::create(*context_, pixels_per_degree(ViewingConditions{}), sequence.width(),
                                              sequence.height());
            if (!created) return std::unexpected(created.error());
            flip = std::move(*created);
        }
        auto resolve =
            TaaResolve::create(*context_, (*shader)->variant(), sequence.width(), sequence.height(), options);
        if (!resolve) return std::unexpected(resolve.error());
        auto m = measure_sequence(**resolve, sequence, warmup_, device_flip_mean(*flip));
        if (!m) return fail(fmt::format("{} on {}: {}", set.name, sequence.name(), m.error().message));
        measured.push_back(*m);
    }
    return measured;
}

} // namespace kdop::cli
