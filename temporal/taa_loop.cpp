#include "taa_loop.h"

namespace kdop {

Result<std::unique_ptr<TaaLoop>> TaaLoop::create(const Context& context, const Variant& shader,
                                                 const Image& background) {
    std::unique_ptr<TaaLoop> loop(new TaaLoop(background));
    auto kernel = Kernel::create(context, shader);
    if (!kernel) return std::unexpected(kernel.error());
    loop->kernel_ = std::move(*kernel);
    auto pass = RectifyPass::create(context, background.width, background.height, TextureFormat::rgba32f);
    if (!pass) return std::unexpected(pass.error());
    loop->pass_ = std::move(*pass);
    loop->history_ = Image(background.width, background.height);
    return loop;
}

Result<Image> TaaLoop::dispatch(const FrameState& s, const Image& history, float current_weight) {
    if (auto ok = pass_->upload(background_, history); !ok) return std::unexpected(ok.error());
    auto pair = [](const char* name, glm::vec2 v) { return RectifyPass::PushConstantValue{name, {v.x, v.y}}; };
    const RectifyPass::PushConstantValue values[] = {
        pair("jitter", s.jitter),
        pair("car_center", s.car_center),
        pair("car_motion", s.car_motion),
        pair("shadow_center", s.shadow_center),
        pair("shadow_motion", s.shadow_motion),
        {"current_weight", {current_weight}},
        {"gamma", {kVarianceGamma}},
    };
    if (auto timing = pass_->dispatch(*kernel_, values); !timing) return std::unexpected(timing.error());
    return pass_->download();
}

Result<Image> TaaLoop::render(const FrameState& state) { return dispatch(state, history_, 1.0f); }

Result<const Image*> TaaLoop::advance(const FrameState& state) {
    auto frame = dispatch(state, history_, has_history_ ? kCurrentWeight : 1.0f);
    if (!frame) return std::unexpected(frame.error());
    history_ = std::move(*frame);
    has_history_ = true;
    return &history_;
}

} // namespace kdop
