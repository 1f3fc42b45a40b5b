// The TAA loop on the device: one frame shader (taa_shader.h) dispatched once per frame through a
// RectifyPass, whose three bindings it uses as background texture, history and output. The output
// of each frame is read back and becomes the next frame's history, so every frame the metrics see
// is the one the loop continues from.
#pragma once

#include "context.h"
#include "image.h"
#include "kernel.h"
#include "rectify_pass.h"
#include "result.h"
#include "taa_scene.h"

#include <kdop/variant.h>

#include <memory>

namespace kdop {

// The blend weight of the current frame: each frame keeps 90% of the rectified history. The
// introduction to TAA in shared/reference gives 0.05 to 0.1 as the usual range; at 0.1 the history
// averages about ten frames, the length of the R2 jitter cycle.
inline constexpr float kCurrentWeight = 0.1f;
// Salvi's recommended variance-clip width, as in the paper's +Var rows.
inline constexpr float kVarianceGamma = 1.0f;

class TaaLoop {
public:
    // `shader` is a TAA frame shader; `background` sets the frame's size.
    static Result<std::unique_ptr<TaaLoop>> create(const Context& context, const Variant& shader,
                                                   const Image& background);

    // The scene at `state` with no history: the aliased frame a renderer without TAA shows, the
    // ghosting reference. The history is not touched.
    Result<Image> render(const FrameState& state);
    // One TAA frame: render at `state`, reproject the history, rectify, blend. The first frame after
    // create() or restart() has no history and is rendered alone.
    Result<const Image*> advance(const FrameState& state);
    // Forgets the history: the next frame starts a new sequence.
    void restart() { has_history_ = false; }

private:
    TaaLoop(const Image& background) : background_(background) {}
    Result<Image> dispatch(const FrameState& state, const Image& history, float current_weight);

    Image background_;
    std::unique_ptr<Kernel> kernel_;
    std::unique_ptr<RectifyPass> pass_;
    Image history_;
    bool has_history_ = false;
};

} // namespace kdop
