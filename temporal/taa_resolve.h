// The TAA resolve on the device: one resolve shader (taa_shader.h) dispatched once per frame
// through a RectifyPass with the resolve's inputs (color, history, motion, depth). The output of
// each frame is read back and becomes the next frame's history, so every frame the metrics see is
// the one the resolve continues from.
#pragma once

#include "core/result.h"
#include "images/image.h"
#include "runtime/context.h"
#include "runtime/kernel.h"
#include "runtime/rectify_pass.h"
#include "sequence/frame_source.h"
#include "temporal/resolve_options.h"

#include <kdop/variant.h>

#include <memory>

namespace kdop {

class TaaResolve {
public:
    // `shader` is a resolve built with `options` (build_taa_shader); frames are width x height.
    static Result<std::unique_ptr<TaaResolve>> create(const Context& context, const Variant& shader,
                                                      std::uint32_t width, std::uint32_t height,
                                                      const ResolveOptions& options);

    // One frame: reproject the history by the frame's motion, rectify, blend. With `starts_history`
    // (the first frame, a camera cut) the output is the frame's color. The pointer stays valid until
    // the next call.
    Result<const Image*> advance(const LoadedFrame& frame, bool starts_history);

private:
    TaaResolve(std::uint32_t width, std::uint32_t height, const ResolveOptions& options)
        : options_(options), width_(width), height_(height) {}

    ResolveOptions options_;
    std::uint32_t width_, height_;
    std::unique_ptr<Kernel> kernel_;
    std::unique_ptr<RectifyPass> pass_;
    Image history_, motion_, nothing_; // nothing_: motion and depth where a frame has none
};

} // namespace kdop
