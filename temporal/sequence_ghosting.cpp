#include "temporal/sequence_ghosting.h"

#include "flip/flip.h"
#include "generator/variant_spec.h"

#include <fmt/format.h>

namespace kdop {

Result<std::unique_ptr<SequenceGhosting>> SequenceGhosting::create(const std::vector<std::string>& dirs,
                                                                   InputSpace space, const ResolveOptions& options,
                                                                   std::uint32_t warmup) {
    auto out = std::unique_ptr<SequenceGhosting>(new SequenceGhosting);
    out->options_.resolve = options;
    out->options_.schedule.warmup = warmup;
    out->options_.ppd = pixels_per_degree(ViewingConditions{});
    auto context = Context::create({});
    if (!context) return std::unexpected(context.error());
    out->context_ = std::move(*context);
    for (const std::string& dir : dirs) {
        auto sequence = read_resolvable_sequence(dir, warmup, options);
        if (!sequence) return std::unexpected(sequence.error());
        if (!sequence->measure.ghosting)
            return fail(fmt::format("--sequence {}: its sequence.json measures only shimmer (\"measure\"), and the "
                                    "fit is judged by ghosting",
                                    dir));
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
    if (!evaluation_) {
        auto created = TaaEvaluation::create(*context_, {spec}, options_);
        if (!created) return std::unexpected(created.error());
        evaluation_ = std::make_unique<TaaEvaluation>(std::move(*created));
    } else if (auto ok = evaluation_->set_variants({spec}); !ok) {
        return std::unexpected(ok.error());
    }
    std::vector<SequenceMeasurement> measured;
    for (const SequenceFrames& sequence : sequences_) {
        auto rows = evaluation_->measure(sequence);
        if (!rows) return std::unexpected(rows.error());
        const EvaluationRow& row = rows->front();
        measured.push_back({.means = row.means,
                            .range = row.range,
                            .against_reference = row.against_reference,
                            .frames = row.per_frame.size(),
                            .per_frame = row.per_frame,
                            .notes = row.notes});
    }
    return measured;
}

} // namespace kdop
