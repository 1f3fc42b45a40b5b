// How kdop taa's pictures and report.html's viewer compare and show frames: as the figures were
// measured, LDR-FLIP on LDR frames as they are, HDR-FLIP (at the run's exposures) on HDR frames,
// which are shown tone mapped at exposure 0 with HDR-FLIP's tone mapper.
#pragma once

#include "core/result.h"
#include "flip/hdr_flip.h"
#include "sequence/sequence.h"
#include "temporal/taa_measure.h"

#include <string>
#include <vector>

namespace kdop {

struct PictureFlip {
    FlipMean flip; // the figures' (TaaEvaluation::flip_mean), whose evaluator must outlive this
    ColorRange range = ColorRange::ldr;
    ExposureOptions exposure; // HDR-FLIP's, for hdr, as `flip` was made with

    // Each pixel's FLIP of `test` against `reference`, as the figures measure it. `same_reference`:
    // `reference` is the Image of the call before, unchanged (FlipMean).
    Result<std::vector<float>> map(const Image& reference, const Image& test, bool same_reference = false) const;
    // `image` as a picture shows it: LDR as it is, HDR tone mapped.
    Image shown(const Image& image) const;
    const char* name() const { return range == ColorRange::hdr ? "HDR-FLIP" : "LDR-FLIP"; }
};

} // namespace kdop
