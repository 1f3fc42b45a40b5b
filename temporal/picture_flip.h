// How kdop taa's pictures and report.html's viewer compare and show frames: as the figures were
// measured, LDR-FLIP on LDR frames as they are, HDR-FLIP (at the run's exposures) on HDR frames,
// which are shown tone mapped at exposure 0 with HDR-FLIP's tone mapper.
#pragma once

#include "core/result.h"
#include "flip/hdr_flip.h"
#include "sequence/sequence.h"
#include "temporal/flip_evaluator.h"

#include <string>
#include <vector>

namespace kdop {

class PictureFlip {
public:
    // `flip` is the figures' (TaaEvaluation::flip_evaluator), done measuring, and must outlive this.
    PictureFlip(FlipEvaluator& flip, ColorRange range) : flip_(&flip), range_(range) {}

    // Each pixel's FLIP of `test` against `reference`, as the figures measure it. `same_reference`:
    // `reference` holds the pixels of the call before's, whose work the device keeps.
    Result<std::vector<float>> map(const Image& reference, const Image& test, bool same_reference = false);
    // `image` as a picture shows it: LDR as it is, HDR tone mapped.
    Image shown(const Image& image) const;
    ColorRange range() const { return range_; }
    const char* name() const { return range_ == ColorRange::hdr ? "HDR-FLIP" : "LDR-FLIP"; }

private:
    FlipEvaluator* flip_;
    ColorRange range_;
    FrameHandle reference_; // the last map's, in the evaluator's store
};

} // namespace kdop
