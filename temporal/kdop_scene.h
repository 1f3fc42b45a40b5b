// A scene kdop draws itself, for `kdop taa` to measure and `kdop scene` to write: the 3-D testbed's
// (grass3d, asphalt3d: testbed/, rasterized on the device, the default) or a 2-D one (grass,
// asphalt, a real texture, a user's background: taa_scene.h, drawn on the CPU). Each is measured as
// the paper measures its scenes: shimmer on a still, jittered sequence and ghosting on a moving one
// without jitter (taa_measure.h).
#pragma once

#include "context.h"
#include "frame_source.h"
#include "image_io.h"
#include "result.h"
#include "trail_picture.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace kdop {

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

struct SceneOptions {
    std::uint32_t width = 320, height = 180;
    std::uint64_t seed = 1;                         // of the synthetic textures and the testbed's scenes
    InputSpace input_space = InputSpace::from_file; // of --background images
    const Context* context = nullptr;               // where the 3-D scenes are drawn; must outlive them
    bool camera_pan = false;                        // 3-D scenes: the camera slides sideways (--camera pan)
    std::uint32_t reference_samples = 0;            // 3-D scenes: > 0 adds a supersampled reference per frame
};

// The built-in scenes: the 3-D testbed's two, then the 2-D ones.
std::vector<std::string> builtin_scene_names();

// Whether select_taa_scenes(names, backgrounds, ...) picks a 3-D scene, and so needs a context.
bool selects_testbed_scene(const std::vector<std::string>& names, const std::vector<std::string>& backgrounds);

// The scenes `names` asks for (built-in, by name), then one per image in `backgrounds` (2-D), in
// that order; both empty: grass3d and asphalt3d. Errors name the option (--scenes, --background).
Result<std::vector<std::shared_ptr<const TaaScene>>> select_taa_scenes(const std::vector<std::string>& names,
                                                                       const std::vector<std::string>& backgrounds,
                                                                       const SceneOptions& options);

} // namespace kdop
