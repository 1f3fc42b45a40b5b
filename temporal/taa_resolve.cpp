#include "temporal/taa_resolve.h"

#include <fmt/format.h>

namespace kdop {
namespace {

// The inputs of shader_templates/taa_resolve.comp.in.
constexpr const char* kColor = "color_frame";
constexpr const char* kHistory = "history_frame"; // one per shader, kept on the device
constexpr const char* kMotion = "motion_frame";
constexpr const char* kDepth = "depth_frame";

} // namespace

Result<std::unique_ptr<TaaResolve>> TaaResolve::create(const Context& context, const Variant& shader,
                                                       std::uint32_t width, std::uint32_t height,
                                                       const ResolveOptions& options) {
    const Variant* shaders[] = {&shader};
    return create(context, shaders, width, height, options);
}

Result<std::unique_ptr<TaaResolve>> TaaResolve::create(const Context& context, std::span<const Variant* const> shaders,
                                                       std::uint32_t width, std::uint32_t height,
                                                       const ResolveOptions& options, std::vector<std::string> names) {
    return create(context, shaders, width, height, width, height, options, std::move(names));
}

Result<std::unique_ptr<TaaResolve>> TaaResolve::create(const Context& context, std::span<const Variant* const> shaders,
                                                       std::uint32_t input_width, std::uint32_t input_height,
                                                       std::uint32_t width, std::uint32_t height,
                                                       const ResolveOptions& options, std::vector<std::string> names) {
    if (shaders.empty()) return fail("a resolve of no shader");
    if (!names.empty() && names.size() != shaders.size()) return fail("a resolve's shaders and names differ in count");
    const bool smaller = input_width != width || input_height != height;
    if (smaller != options.upscale)
        return fail(fmt::format("internal error: a resolve of {}x{} frames to {}x{} built {}for upscaling", input_width,
                                input_height, width, height, options.upscale ? "" : "not "));
    std::unique_ptr<TaaResolve> r(new TaaResolve(context, options));
    r->input_width_ = input_width, r->input_height_ = input_height;
    r->width_ = width, r->height_ = height;
    r->names_ = std::move(names);
    if (r->names_.empty())
        for (const Variant* shader : shaders) r->names_.push_back(shader->name);
    for (const Variant* shader : shaders) {
        auto kernel = Kernel::create(context, *shader);
        if (!kernel) return std::unexpected(kernel.error());
        r->kernels_.push_back(std::move(*kernel));
    }
    r->outputs_.resize(shaders.size());
    // In the order advance_all() uploads them; motion and depth with the channels they have.
    auto pass = RectifyPass::create(context, width, height, TextureFormat::rgba32f,
                                    std::vector<PassInput>{{kColor, 4, input_width, input_height},
                                                           {kHistory, 4},
                                                           {kMotion, 2, input_width, input_height},
                                                           {kDepth, 1, input_width, input_height}});
    if (!pass) return std::unexpected(pass.error());
    r->pass_ = std::move(*pass);
    // Every shader's history, zero until its first frame.
    if (auto ok = r->pass_->add_slots(kHistory, shaders.size()); !ok) return std::unexpected(ok.error());
    r->zeros_.assign(2 * std::size_t(input_width) * input_height, 0.0f);
    return r;
}

Result<const Image*> TaaResolve::advance(const LoadedFrame& frame, bool starts_history) {
    if (auto ok = advance_all(frame, starts_history); !ok) return std::unexpected(ok.error());
    return &outputs_.front();
}

Result<void> TaaResolve::advance_all(const LoadedFrame& frame, bool starts_history, bool read_outputs) {
    if (frame.color.width != input_width_ || frame.color.height != input_height_)
        return fail(fmt::format("a {}x{} frame for a resolve of {}x{} frames", frame.color.width, frame.color.height,
                                input_width_, input_height_));
    if (auto ok = check_mappable(options_.color_map, frame.color.pixels, input_width_, "color"); !ok)
        return std::unexpected(ok.error());
    const bool has_motion = !starts_history;
    const std::size_t pixels = std::size_t(input_width_) * input_height_;
    if (has_motion && frame.motion.size() != pixels) return fail("a frame with a history but no motion");
    if (options_.dilate_motion && has_motion && !frame.depth)
        return fail("--dilate-motion takes the motion of the nearest neighbor, and this frame has no depth");
    // The frame's inputs once; then each shader's own history, its dispatch and its output. Depth
    // only reaches the device where the shader reads it.
    const Image* frame_inputs[] = {&frame.color, nullptr, nullptr,
                                   options_.dilate_motion && frame.depth ? &*frame.depth : nullptr};
    if (auto ok = pass_->upload(frame_inputs); !ok) return std::unexpected(ok.error());
    const std::span<const float> motion =
        has_motion ? std::span<const float>(&frame.motion[0].x, 2 * pixels) : std::span<const float>(zeros_);
    if (auto ok = pass_->upload(kMotion, motion); !ok) return std::unexpected(ok.error());
    if (options_.dilate_motion && !frame.depth)
        if (auto ok = pass_->upload(kDepth, std::span<const float>(zeros_).first(pixels)); !ok)
            return std::unexpected(ok.error());
    return resolve_all(starts_history, read_outputs, frame.jitter);
}

Result<LoadedFrame> TaaResolve::advance_all(const DeviceFrames& frames, std::size_t index, bool starts_history,
                                            bool read_outputs, bool read_frame) {
    std::vector<std::string_view> names{kColor, kMotion};
    if (options_.dilate_motion) names.push_back(kDepth);
    auto images = pass_->images_to_fill(names);
    if (!images) return std::unexpected(images.error());
    // A frame that starts a history resolves without motion, as the other advance_all gives it.
    const RasterTargets targets{(*images)[0], starts_history ? VK_NULL_HANDLE : (*images)[1],
                                options_.dilate_motion ? (*images)[2] : VK_NULL_HANDLE};
    if (starts_history)
        if (auto ok = pass_->upload(kMotion, zeros_); !ok) return std::unexpected(ok.error());
    auto frame = frames.draw_into(index, targets, read_frame);
    if (!frame) return frame;
    if (auto ok = resolve_all(starts_history, read_outputs, frame->jitter); !ok) return std::unexpected(ok.error());
    return frame;
}

Result<VkImageView> TaaResolve::output_on_device(std::size_t s) {
    if (auto ok = pass_->select_slot(kHistory, s); !ok) return std::unexpected(ok.error());
    return pass_->view_to_sample(kHistory);
}

Result<void> TaaResolve::resolve_all(bool starts_history, bool read_outputs, glm::vec2 jitter) {
    // The upscaling ratio, as FSR 2 and UE4 take it: output width over input width.
    const float ratio = float(width_) / float(input_width_);
    const RectifyPass::PushConstantValue all[] = {
        {"current_weight", {starts_history ? 1.0f : options_.current_weight}},
        {"gamma", {options_.gamma * (options_.upscale ? box_scale_at(options_.box_scale, ratio) : 1.0f)}},
        {"jitter", {jitter.x, jitter.y}},
        {"sample_distance", {options_.sample_distance.at(ratio)}},
    };
    // Only an upscaling resolve takes the jitter and the sample distance.
    const std::span<const RectifyPass::PushConstantValue> values = std::span(all).first(options_.upscale ? 4 : 2);
    for (std::size_t s = 0; s < kernels_.size(); ++s) {
        auto resolved = [&]() -> Result<void> {
            if (auto ok = pass_->select_slot(kHistory, s); !ok) return ok;
            if (auto timing = pass_->dispatch(*kernels_[s], values); !timing) return std::unexpected(timing.error());
            if (auto ok = pass_->copy_output_to(kHistory); !ok) return ok;
            if (!read_outputs) return {};
            auto out = pass_->download();
            if (!out) return std::unexpected(out.error());
            outputs_[s] = std::move(*out);
            return {};
        }();
        if (!resolved) return fail(fmt::format("{}: {}", names_[s], resolved.error().message));
    }
    return {};
}

} // namespace kdop
