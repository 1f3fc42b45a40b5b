// A frame source that draws its frames on the device (the 3-D testbed, testbed/scene3d_frames.h)
// and can leave a frame there: drawn and copied into the images a compute pass samples. What lets
// the TAA resolve take its frames without a round trip through the host (FrameSource::
// device_frames): motion and depth never come back, and the color and reference only for the
// frames a measurement compares with.
#pragma once

#include "core/result.h"
#include "runtime/raster_pass.h"
#include "sequence/sequence.h"

#include <cstddef>

namespace kdop {

class DeviceFrames {
public:
    virtual ~DeviceFrames() = default;
    // Frame `index`, the one FrameSource::frame(index) reads back, drawn into `targets`: its color,
    // motion and depth, the same floats. With `read_back`, what comes back is the frame's color and,
    // where the source has them, its reference, as frame() gives them (without motion and depth);
    // else an empty frame. Errors name the frame.
    virtual Result<LoadedFrame> draw_into(std::size_t index, const RasterTargets& targets, bool read_back) const = 0;
};

} // namespace kdop
