#include "temporal/taa_resolve.h"

#include <fmt/format.h>

namespace kdop {

Result<std::unique_ptr<TaaResolve>> TaaResolve::create(const Context& context, const Variant& shader,
                                                       std::uint32_t width, std::uint32_t height,
                                                       const ResolveOptions& options) {
    std::unique_ptr<TaaResolve> r(new TaaResolve(width, height, options));
    auto kernel = Kernel::create(context, shader);
    if (!kernel) return std::unexpected(kernel.error());
    r->kernel_ = std::move(*kernel);
    // The names of shader_templates/taa_resolve.comp.in, in the order advance() uploads them.
    auto pass = RectifyPass::create(context, width, height, TextureFormat::rgba32f,
                                    {"color_frame", "history_frame", "motion_frame", "depth_frame"});
    if (!pass) return std::unexpected(pass.error());
    r->pass_ = std::move(*pass);
    r->history_ = Image(width, height);
    r->motion_ = Image(width, height, glm::vec4(0));
    r->nothing_ = Image(width, height, glm::vec4(0));
    return r;
}

Result<const Image*> TaaResolve::advance(const LoadedFrame& frame, bool starts_history) {
    if (frame.color.width != width_ || frame.color.height != height_)
        return fail(
            fmt::format("a {}x{} frame for a {}x{} resolve", frame.color.width, frame.color.height, width_, height_));
    if (auto ok = check_mappable(options_.color_map, frame.color.pixels, width_, "color"); !ok)
        return std::unexpected(ok.error());
    const bool has_motion = !starts_history;
    if (has_motion) {
        if (frame.motion.size() != motion_.pixels.size()) return fail("a frame with a history but no motion");
        for (std::size_t i = 0; i < frame.motion.size(); ++i) motion_.pixels[i] = glm::vec4(frame.motion[i], 0, 0);
    }
    if (options_.dilate_motion && has_motion && !frame.depth)
        return fail("--dilate-motion takes the motion of the nearest neighbor, and this frame has no depth");
    // Depth only reaches the device where the shader reads it.
    const Image* depth = !options_.dilate_motion ? nullptr : frame.depth ? &*frame.depth : &nothing_;
    const Image* inputs[] = {&frame.color, &history_, has_motion ? &motion_ : &nothing_, depth};
    if (auto ok = pass_->upload(inputs); !ok) return std::unexpected(ok.error());
    const RectifyPass::PushConstantValue values[] = {
        {"current_weight", {starts_history ? 1.0f : options_.current_weight}},
        {"gamma", {options_.gamma}},
    };
    if (auto timing = pass_->dispatch(*kernel_, values); !timing) return std::unexpected(timing.error());
    auto out = pass_->download();
    if (!out) return std::unexpected(out.error());
    history_ = std::move(*out);
    return &history_;
}

} // namespace kdop
