#include "scenes/taa_scene.h"

namespace kdop {

std::shared_ptr<const FrameSource> shimmer_frames(const TaaScene& scene, const TaaSchedule& schedule) {
    return std::make_shared<MeasuredFor>(
        scene.frames(scene.name() + "-shimmer", schedule.warmup + schedule.frames, false, true),
        SequenceRoles{.ghosting = false, .shimmer = true});
}

std::shared_ptr<const FrameSource> ghosting_frames(const TaaScene& scene, const TaaSchedule& schedule) {
    return std::make_shared<MeasuredFor>(
        scene.frames(scene.name() + "-ghosting", schedule.warmup + schedule.frames, true, false),
        SequenceRoles{.ghosting = true, .shimmer = false});
}

} // namespace kdop
