// The shimmer and ghosting of fitted axis sets on frame sequences, measured as `kdop taa
// --sequence` measures them (through the same evaluation, taa_evaluation.h): the set's clip generated and built into
// the TAA resolve with the given resolve options, run over each sequence on the device after the warmup, measured with
// the device's FLIP (HDR-FLIP for an HDR sequence). kdop optimize --target-ghosting chooses k by it.
#pragma once

#include "core/result.h"
#include "flip/device_flip.h"
#include "generator/axis_set.h"
#include "runtime/context.h"
#include "sequence/frame_source.h"
#include "temporal/resolve_options.h"
#include "temporal/taa_evaluation.h"
#include "temporal/taa_measure.h"

#include <kdop/variant.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace kdop {

class SequenceGhosting {
public:
    // Reads the sequences' manifests and opens the device (lavapipe unless KDOP_DEVICE says
    // otherwise). Refuses a sequence with no frame left after the warmup.
    static Result<std::unique_ptr<SequenceGhosting>> create(const std::vector<std::string>& dirs, InputSpace space,
                                                            const ResolveOptions& options, std::uint32_t warmup);

    // `set`'s clip on every sequence, in the order given.
    Result<std::vector<SequenceMeasurement>> measure(const AxisSet& set, Neighborhood shape);

private:
    std::vector<SequenceFrames> sequences_;
    EvaluationOptions options_;
    std::unique_ptr<Context> context_;
    std::unique_ptr<TaaEvaluation> evaluation_; // made with the first set, then given each next one
};

} // namespace kdop
