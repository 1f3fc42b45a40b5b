#include "temporal/taa_resolve.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

namespace kdop {
namespace {

// The inputs of shader_templates/taa_resolve.comp.in.
constexpr const char* kColor = "color_frame";
constexpr const char* kHistory = "history_frame"; // one per shader, kept on the device
constexpr const char* kMotion = "motion_frame";
constexpr const char* kDepth = "depth_frame";

// What the pass gives a binding of each role.
std::string_view pass_input(ResourceRole role) {
    switch (role) {
    case ResourceRole::current: return kColor;
    case ResourceRole::history: return kHistory;
    case ResourceRole::motion: return kMotion;
    case ResourceRole::depth: return kDepth;
    case ResourceRole::output: return RectifyPass::kOutput;
    case ResourceRole::sampler: return RectifyPass::kSampler;
    }
    return {};
}

bool same(const MotionConvention& a, const MotionConvention& b) {
    return a.units == b.units && a.points_to == b.points_to && a.y_axis == b.y_axis;
}

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
                                                       const ResolveOptions& options, std::vector<std::string> names,
                                                       std::vector<const BoundResolve*> roles) {
    if (shaders.empty()) return fail("a resolve of no shader");
    if (!names.empty() && names.size() != shaders.size()) return fail("a resolve's shaders and names differ in count");
    if (!roles.empty() && roles.size() != shaders.size()) return fail("a resolve's shaders and roles differ in count");
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
    r->reads_depth_ = options.dilate_motion;
    r->roles_ = std::move(roles);
    r->as_.resize(shaders.size());
    const BoundResolve* first = nullptr; // the first shader's with roles
    for (std::size_t s = 0; s < r->roles_.size(); ++s) {
        const BoundResolve* bound = r->roles_[s];
        if (!bound) continue;
        if (!first) first = bound;
        if (!same(bound->motion, first->motion))
            return fail("internal error: the shaders of one resolve declare different motion conventions");
        for (const BoundResolve::Resource& resource : bound->resources) {
            r->as_[s].push_back({resource.binding->name, pass_input(resource.role)});
            if (resource.role == ResourceRole::depth) r->reads_depth_ = true;
        }
    }
    if (first) {
        r->motion_scale_ = motion_scale(first->motion, input_width, input_height);
        // kdop's own shaders read kdop's motion: they cannot share the upload with a conversion.
        if (!r->takes_device_frames() && std::find(r->roles_.begin(), r->roles_.end(), nullptr) != r->roles_.end())
            return fail("internal error: kdop's resolve beside one that reads its motion in another convention");
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

Result<void> TaaResolve::advance_all(const LoadedFrame& frame, bool starts_history, bool read_outputs,
                                     std::uint32_t index) {
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
    if (reads_depth_ && !options_.dilate_motion && !frame.depth)
        return fail("the resolve reads depth (its map's depth role), and this frame has none");
    // The frame's inputs once; then each shader's own history, its dispatch and its output. Depth
    // only reaches the device where the shader reads it.
    const Image* frame_inputs[] = {&frame.color, nullptr, nullptr,
                                   reads_depth_ && frame.depth ? &*frame.depth : nullptr};
    if (auto ok = pass_->upload(frame_inputs); !ok) return std::unexpected(ok.error());
    std::span<const float> motion =
        has_motion ? std::span<const float>(&frame.motion[0].x, 2 * pixels) : std::span<const float>(zeros_);
    if (has_motion && !takes_device_frames()) {
        // In the convention the shaders declare (zero motion is zero in every convention).
        scaled_.resize(2 * pixels);
        for (std::size_t i = 0; i < pixels; ++i) {
            scaled_[2 * i] = frame.motion[i].x * motion_scale_.x;
            scaled_[2 * i + 1] = frame.motion[i].y * motion_scale_.y;
        }
        motion = scaled_;
    }
    if (auto ok = pass_->upload(kMotion, motion); !ok) return std::unexpected(ok.error());
    if (reads_depth_ && !frame.depth)
        if (auto ok = pass_->upload(kDepth, std::span<const float>(zeros_).first(pixels)); !ok)
            return std::unexpected(ok.error());
    return resolve_all(starts_history, read_outputs, frame.jitter, index);
}

Result<LoadedFrame> TaaResolve::advance_all(const DeviceFrames& frames, std::size_t index, bool starts_history,
                                            bool read_outputs, bool read_frame) {
    if (!takes_device_frames())
        return fail("internal error: frames drawn on the device for a resolve whose motion is converted on the host");
    std::vector<std::string_view> names{kColor, kMotion};
    if (reads_depth_) names.push_back(kDepth);
    auto images = pass_->images_to_fill(names);
    if (!images) return std::unexpected(images.error());
    // A frame that starts a history resolves without motion, as the other advance_all gives it.
    const RasterTargets targets{(*images)[0], starts_history ? VK_NULL_HANDLE : (*images)[1],
                                reads_depth_ ? (*images)[2] : VK_NULL_HANDLE};
    if (starts_history)
        if (auto ok = pass_->upload(kMotion, zeros_); !ok) return std::unexpected(ok.error());
    auto frame = frames.draw_into(index, targets, read_frame);
    if (!frame) return frame;
    if (auto ok = resolve_all(starts_history, read_outputs, frame->jitter, std::uint32_t(index)); !ok)
        return std::unexpected(ok.error());
    return frame;
}

Result<VkImageView> TaaResolve::output_on_device(std::size_t s) {
    if (auto ok = pass_->select_slot(kHistory, s); !ok) return std::unexpected(ok.error());
    return pass_->view_to_sample(kHistory);
}

std::vector<std::uint32_t> TaaResolve::role_words(ValueRole role, const FrameValues& frame) const {
    // The upscaling ratio, as FSR 2 and UE4 take it: output width over input width.
    const float ratio = float(width_) / float(input_width_);
    std::vector<float> floats;
    switch (role) {
    case ValueRole::current_weight: floats = {frame.starts_history ? 1.0f : options_.current_weight}; break;
    case ValueRole::gamma:
        floats = {options_.gamma * (options_.upscale ? box_scale_at(options_.box_scale, ratio) : 1.0f)};
        break;
    case ValueRole::jitter: floats = {frame.jitter.x, frame.jitter.y}; break;
    case ValueRole::input_size: floats = {float(input_width_), float(input_height_)}; break;
    case ValueRole::output_size: floats = {float(width_), float(height_)}; break;
    case ValueRole::frame_index: return {frame.index};
    case ValueRole::reset: return {frame.starts_history ? 1u : 0u};
    case ValueRole::exposure: floats = {1.0f}; break; // no source kdop reads gives one yet
    case ValueRole::sample_distance: floats = {options_.sample_distance.at(ratio)}; break;
    }
    std::vector<std::uint32_t> words(floats.size());
    std::memcpy(words.data(), floats.data(), 4 * floats.size());
    return words;
}

std::vector<RectifyPass::PushConstantValue> TaaResolve::push_values(std::size_t s, const FrameValues& frame) const {
    auto value = [&](ValueRole role) {
        std::vector<float> floats(role == ValueRole::jitter ? 2 : 1);
        std::memcpy(floats.data(), role_words(role, frame).data(), 4 * floats.size());
        return floats;
    };
    if (roles_.empty() || !roles_[s]) {
        // kdop's resolve: only an upscaling one takes the jitter and the sample distance.
        std::vector<RectifyPass::PushConstantValue> values{{"current_weight", value(ValueRole::current_weight)},
                                                           {"gamma", value(ValueRole::gamma)}};
        if (options_.upscale)
            values.insert(values.end(), {{"jitter", value(ValueRole::jitter)},
                                         {"sample_distance", value(ValueRole::sample_distance)}});
        return values;
    }
    std::vector<RectifyPass::PushConstantValue> values;
    for (const BoundResolve::Value& v : roles_[s]->values)
        values.push_back(RectifyPass::PushConstantValue::words(v.member->name, role_words(v.role, frame)));
    return values;
}

std::vector<std::pair<std::string_view, std::vector<std::byte>>>
TaaResolve::uniform_blocks(std::size_t s, const FrameValues& frame) const {
    std::vector<std::pair<std::string_view, std::vector<std::byte>>> blocks;
    if (roles_.empty() || !roles_[s]) return blocks;
    for (const BoundResolve::Uniform& u : roles_[s]->uniforms) {
        auto block =
            std::find_if(blocks.begin(), blocks.end(), [&](const auto& b) { return b.first == u.block->name; });
        if (block == blocks.end())
            block = blocks.insert(blocks.end(), {u.block->name, std::vector<std::byte>(u.block->block_size)});
        const std::vector<std::uint32_t> words = role_words(u.role, frame);
        std::memcpy(block->second.data() + u.offset, words.data(), std::min<std::size_t>(u.size, 4 * words.size()));
    }
    return blocks;
}

Result<void> TaaResolve::resolve_all(bool starts_history, bool read_outputs, glm::vec2 jitter, std::uint32_t index) {
    const FrameValues frame{starts_history, jitter, index};
    for (std::size_t s = 0; s < kernels_.size(); ++s) {
        auto resolved = [&]() -> Result<void> {
            if (auto ok = pass_->select_slot(kHistory, s); !ok) return ok;
            const auto values = push_values(s, frame);
            const auto blocks = uniform_blocks(s, frame);
            std::vector<RectifyPass::UniformBlock> uniforms;
            for (const auto& [name, bytes] : blocks) uniforms.push_back({name, bytes});
            if (auto timing = pass_->dispatch(*kernels_[s], values, as_[s], uniforms); !timing)
                return std::unexpected(timing.error());
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
