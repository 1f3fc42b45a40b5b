// Shimmer and ghosting of one TAA frame shader on one scene, as Ikkala et al. 2024 measure them
// (Sec. 4), in LDR-FLIP (flip/flip.h):
//   shimmer:  jitter on, no animation; after `warmup` frames, the mean FLIP between each frame and
//             the one before it, over `frames` frames. Only the loop's rejection of valid history
//             makes successive frames differ, so this is the temporal instability clipping causes.
//   ghosting: jitter off, animation on; after `warmup` frames, the mean FLIP between each frame
//             and the aliased frame of the same instant (TaaLoop::render), over `frames` frames.
//             With jitter off the loop no longer antialiases, so what is left is the ghosting.
#pragma once

#include "flip.h"
#include "image.h"
#include "result.h"
#include "taa_loop.h"
#include "trail_picture.h"

#include <cstdint>
#include <functional>

namespace kdop {

struct TaaSchedule {
    std::uint32_t warmup = 100; // frames before measuring, so the history is full
    std::uint32_t frames = 100; // frames measured
};

struct TaaMeasurement {
    double shimmer = 0, ghosting = 0;
    // The ghosting sequence's frame trail_frame(schedule): where a trail is longest.
    Image trail;
};

// Which frame of the ghosting sequence the pictures show: of the measured frames, the one where
// the red box moves fastest, so its trail is longest.
std::uint32_t trail_frame(const TaaSchedule& schedule, std::uint32_t width, std::uint32_t height);

// The part of that frame the pictures show: half the frame's width and height around the red box,
// shifted toward where it came from, so its trail is in view.
TrailCrop trail_crop(const TaaSchedule& schedule, std::uint32_t width, std::uint32_t height);

// Runs both sequences on `loop` (2 x (warmup + frames) + 1 frames); `on_frame` is called after each.
Result<TaaMeasurement> measure_taa(TaaLoop& loop, std::uint32_t width, std::uint32_t height,
                                   const TaaSchedule& schedule, const LdrFlip& flip,
                                   const std::function<void()>& on_frame = {});

// `frame` ready for LDR-FLIP and PNG: the loop's blends and clips land on segments between colors
// in [0, 1], so anything beyond it is float rounding; values within 1e-4 outside are moved onto the
// range, and anything further (a bug, not rounding) is an error naming the pixel.
Result<Image> within_unit_range(const Image& frame, std::string_view what);

} // namespace kdop
