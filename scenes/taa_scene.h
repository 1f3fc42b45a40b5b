// A scene kdop draws itself, for `kdop taa` to measure and `kdop scene` to write: the 3-D testbed's
// (grass3d, asphalt3d: testbed_scene.h over testbed/, rasterized on the device, the default) or a
// 2-D one (grass, asphalt, a real texture, a user's background: sprite_scene.h, drawn on the CPU).
// scene_catalog.h picks them by name. Each is measured as
// the paper measures its scenes: shimmer on a still, jittered sequence and ghosting on a moving one
// without jitter (temporal/taa_measure.h).
#pragma once

#include "core/result.h"
#include "sequence/frame_source.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace kdop {

// The part of each frame shown, magnified `scale` times (nearest, so aliasing stays visible).
struct TrailCrop {
    std::uint32_t x = 0, y = 0, width = 0, height = 0;
    std::uint32_t scale = 1;
};

struct TaaSchedule {
    std::uint32_t warmup = 100; // frames before measuring, so the history is full
    std::uint32_t frames = 100; // frames measured
};

class TaaScene {
public:
    virtual ~TaaScene() = default;
    virtual const std::string& name() const = 0;
    virtual std::uint32_t width() const = 0;
    virtual std::uint32_t height() const = 0;
    // What the scene is made of (textures, counts, seeds), for reports.
    virtual std::string content() const = 0;
    // Frames 0 to `count` - 1, called `name`: the objects moving or as at frame 0, the samples at
    // the R2 jitter or at the pixel centers.
    virtual std::shared_ptr<const FrameSource> frames(const std::string& name, std::size_t count, bool animate,
                                                      bool jitter) const = 0;
    // Which frame of the ghosting sequence the pictures show: of the measured frames, the one where
    // the objects move fastest, so their trails are longest; and the part of it shown, around them.
    virtual std::uint32_t trail_frame(const TaaSchedule& schedule) const = 0;
    virtual TrailCrop trail_crop(const TaaSchedule& schedule) const = 0;
};

// The scene's two sequences, each warmup + frames long: <name>-shimmer (still, jittered) and
// <name>-ghosting (moving, without jitter).
std::shared_ptr<const FrameSource> shimmer_frames(const TaaScene& scene, const TaaSchedule& schedule);
std::shared_ptr<const FrameSource> ghosting_frames(const TaaScene& scene, const TaaSchedule& schedule);

} // namespace kdop
