// A frame source that draws its frames on the device (the 3-D testbed, testbed/scene3d_frames.h)
// and can leave a frame there: drawn and copied into the images a compute pass samples, never
// read back. What lets the TAA resolve take the frames nothing reads on the host (the warm-up)
// without a round trip through it (FrameSource::device_frames).
#pragma once

#include "core/result.h"
#include "runtime/raster_pass.h"

#include <cstddef>

namespace kdop {

class DeviceFrames {
public:
    virtual ~DeviceFrames() = default;
    // Frame `index`, the one FrameSource::frame(index) reads back, drawn into `targets`: its color,
    // motion and depth, the same floats. Errors name the frame.
    virtual Result<void> draw_into(std::size_t index, const RasterTargets& targets) const = 0;
};

} // namespace kdop
