#include "scenes/taa_scene.h"

namespace kdop {

std::shared_ptr<const FrameSource> shimmer_frames(const TaaScene& scene, const TaaSchedule& schedule) {
    return scene.frames(scene.name() + "-shimmer", schedule.warmup + schedule.frames, false, true);
}

std::shared_ptr<const FrameSource> ghosting_frames(const TaaScene& scene, const TaaSchedule& schedule) {
    return scene.frames(scene.name() + "-ghosting", schedule.warmup + schedule.frames, true, false);
}

} // namespace kdop
