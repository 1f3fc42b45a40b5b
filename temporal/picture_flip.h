// How kdop taa's pictures and report.html's viewer compare and show frames: as the figures were
// measured, LDR-FLIP on LDR frames as they are, HDR-FLIP (at the run's exposures) on HDR frames,
// which are shown tone mapped at exposure 0 with HDR-FLIP's tone mapper.
#pragma once

#include "core/result.h"
#include "flip/hdr_flip.h"
#include "sequence/sequence.h"

#include <string>
#include <vector>

namespace kdop {

struct PictureFlip {
    const HdrFlip* flip = nullptr; // must outlive this
    ColorRange range = ColorRange::ldr;
    ExposureOptions exposure; // HDR-FLIP's, for hdr

    // Each pixel's FLIP of `test` against `reference`.
    Result<std::vector<float>> map(const Image& reference, const Image& test) const;
    // `image` as a picture shows it: LDR as it is, HDR tone mapped.
    Image shown(const Image& image) const;
    const char* name() const { return range == ColorRange::hdr ? "HDR-FLIP" : "LDR-FLIP"; }
};

} // namespace kdop
