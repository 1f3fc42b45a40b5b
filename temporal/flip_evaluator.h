// FLIP as a measurement takes it: one call, a reference and a test held in the evaluator's store
// (temporal/output_store.h), the range that picks LDR-FLIP or HDR-FLIP, and whether the per-pixel
// map comes back. Three evaluators stand behind it, each the same figures within device FLIP's
// tolerances of the CPU code (tests/device_flip_test.cpp):
//   cpu_flip_evaluator:    the reference code (flip/flip.h, flip/hdr_flip.h), frames on the host;
//   device_flip_evaluator: FLIP on the device (flip/device_flip.h), with its frames on the host
//                          (uploaded per evaluation, the reference's work kept while it is the same)
//                          or on the device, where a resolve leaves its outputs and FLIP measures
//                          them there (OutputPlacement).
#pragma once

#include "core/result.h"
#include "flip/device_flip.h"
#include "flip/hdr_flip.h"
#include "sequence/frame_source.h"
#include "temporal/output_store.h"

#include <memory>
#include <string>
#include <vector>

namespace kdop {

// The mean FLIP of a pair, and, for HDR-FLIP, how its exposure range departed from the reference
// code's derivation (ExposureRange::note: a black reference, a mostly black one), or nothing.
struct FlipFigure {
    double mean = 0;
    std::string note;
    std::vector<float> map; // with a map asked for: the pair's FLIP per pixel, row-major, the mean's
};

class FlipEvaluator {
public:
    virtual ~FlipEvaluator() = default;
    // Where the frames it compares are kept.
    virtual OutputStore& store() = 0;
    // HDR-FLIP's exposures, for hdr pairs (by default each pair's range, derived from its reference
    // as NVlabs/flip derives it).
    virtual const ExposureOptions& exposures() const = 0;
    // FLIP of `test` against `reference`: LDR-FLIP for an ldr range, HDR-FLIP for hdr; with `map`
    // the per-pixel map too, the one the mean is taken of.
    virtual Result<FlipFigure> evaluate(FrameHandle reference, FrameHandle test, ColorRange range, bool map) = 0;
};

// The CPU's FLIP. `flip` must outlive the evaluator.
std::unique_ptr<FlipEvaluator> cpu_flip_evaluator(const HdrFlip& flip, const ExposureOptions& exposures = {});

// Where device FLIP's frames are kept between the resolve and FLIP.
enum class OutputPlacement {
    host,   // read back and checked on the host (on a CPU device as fast, and one frame a variant less)
    device, // checked and measured where the resolve leaves them; read back only for an observer
};
// The device's FLIP. `flip` must outlive the evaluator and serve no other while it lives.
std::unique_ptr<FlipEvaluator> device_flip_evaluator(DeviceFlip& flip, const ExposureOptions& exposures = {},
                                                     OutputPlacement placement = OutputPlacement::device);

} // namespace kdop
