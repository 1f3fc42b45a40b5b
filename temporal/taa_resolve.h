// The TAA resolve on the device: resolve shaders (taa_shader.h) dispatched once per frame through
// one RectifyPass with the resolve's inputs (color, history, motion, depth). A frame's color,
// motion and depth are uploaded once and every shader resolves it against its own history, so an
// evaluation of several variants draws or reads each frame once. Each shader's history stays on
// the device: its output is copied there as the next frame's history, and read back only when
// asked for (the frames measured), so every frame the metrics see is the one its resolve
// continues from, and a warm-up frame never leaves the device.
#pragma once

#include "core/result.h"
#include "images/image.h"
#include "runtime/context.h"
#include "runtime/kernel.h"
#include "runtime/rectify_pass.h"
#include "sequence/frame_source.h"
#include "temporal/resolve_bindings.h"
#include "temporal/resolve_options.h"
#include "testbed/device_frames.h"

#include <kdop/variant.h>

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace kdop {

class TaaResolve {
public:
    // `shaders` are resolves built with `options` (build_taa_shader), each with its own history;
    // frames are width x height. `names` name the shaders in errors (empty: the shaders' own names).
    static Result<std::unique_ptr<TaaResolve>> create(const Context& context, std::span<const Variant* const> shaders,
                                                      std::uint32_t width, std::uint32_t height,
                                                      const ResolveOptions& options,
                                                      std::vector<std::string> names = {});
    // An upscaling resolve (options.upscale): frames of input_width x input_height in, outputs and
    // histories of width x height. `roles`, one per shader where given: a renderer's own resolve
    // (kdop taa --resolve), bound by the roles its map declares instead of kdop's names; each must
    // outlive the resolve, and all declare one motion convention, to which the motion is converted.
    static Result<std::unique_ptr<TaaResolve>>
    create(const Context& context, std::span<const Variant* const> shaders, std::uint32_t input_width,
           std::uint32_t input_height, std::uint32_t width, std::uint32_t height, const ResolveOptions& options,
           std::vector<std::string> names = {}, std::vector<const BoundResolve*> roles = {});
    // One shader.
    static Result<std::unique_ptr<TaaResolve>> create(const Context& context, const Variant& shader,
                                                      std::uint32_t width, std::uint32_t height,
                                                      const ResolveOptions& options);

    std::size_t size() const { return kernels_.size(); }
    const Context& context() const { return *context_; }
    const std::string& name(std::size_t s) const { return names_[s]; }

    // One frame through every shader: reproject its history by the frame's motion, rectify, blend.
    // With `starts_history` (the first frame, a camera cut) each output is the frame's color. With
    // `read_outputs` each output is also read back, for output(). `index`: the frame's in its
    // sequence, for a resolve that reads it (ValueRole::frame_index).
    Result<void> advance_all(const LoadedFrame& frame, bool starts_history, bool read_outputs = true,
                             std::uint32_t index = 0);

    // Whether frames drawn on the device can go straight into the resolve: not where a shader's
    // motion convention needs the motion converted, which happens on the host.
    bool takes_device_frames() const { return motion_scale_.x == 1 && motion_scale_.y == 1; }
    // Whether a shader reads depth: kdop's with --dilate-motion, a renderer's with a depth role.
    bool reads_depth() const { return reads_depth_; }
    // Shader `s`'s output of the last frame that read them back, valid until the next call.
    const Image& output(std::size_t s) const { return outputs_[s]; }
    // The same, moved out (output(s) is then empty until the next frame read back).
    Image take_output(std::size_t s) { return std::move(outputs_[s]); }

    // The same for frame `index` of a source that draws on the device (FrameSource::device_frames),
    // drawn straight into the resolve's inputs. With `read_frame` its color and reference come back
    // (DeviceFrames::draw_into), for the caller to check and measure with; else the frame never
    // reaches the host, and nothing checks it there.
    Result<LoadedFrame> advance_all(const DeviceFrames& frames, std::size_t index, bool starts_history,
                                    bool read_outputs, bool read_frame);

    // Shader `s`'s output of the last frame where it stays on the device (its next history), read
    // back or not, for another pass on the same queue to sample until the next frame
    // (DeviceFlip::load: the outputs measured where they are).
    Result<VkImageView> output_on_device(std::size_t s);

    // The same for the first shader alone, returning its output.
    Result<const Image*> advance(const LoadedFrame& frame, bool starts_history);

private:
    TaaResolve(const Context& context, const ResolveOptions& options) : context_(&context), options_(options) {}
    // Every shader on the frame in the inputs: its history, its dispatch, its output kept as its
    // next history and, with `read_outputs`, read back. `jitter`: the frame's (upscaling only).
    Result<void> resolve_all(bool starts_history, bool read_outputs, glm::vec2 jitter, std::uint32_t index);
    // What one frame gives the shaders: kdop's push constants by name, and for a renderer's
    // resolve the words of each value role.
    struct FrameValues {
        bool starts_history;
        glm::vec2 jitter;
        std::uint32_t index;
    };
    std::vector<std::uint32_t> role_words(ValueRole role, const FrameValues& frame) const;
    // The push constants of shader `s`: kdop's names, or those its roles give.
    std::vector<RectifyPass::PushConstantValue> push_values(std::size_t s, const FrameValues& frame) const;
    // The bytes of each of shader `s`'s uniform blocks, its roles' values at their offsets.
    std::vector<std::pair<std::string_view, std::vector<std::byte>>> uniform_blocks(std::size_t s,
                                                                                    const FrameValues& frame) const;

    const Context* context_;
    ResolveOptions options_;
    std::uint32_t input_width_ = 0, input_height_ = 0; // the frames'
    std::uint32_t width_ = 0, height_ = 0;             // the outputs and histories
    std::vector<std::unique_ptr<Kernel>> kernels_;
    std::unique_ptr<RectifyPass> pass_;
    std::vector<Image> outputs_; // one per shader, read back
    std::vector<std::string> names_;
    std::vector<const BoundResolve*> roles_;              // one per shader, or empty: kdop's own
    std::vector<std::vector<RectifyPass::BindingAs>> as_; // each shader's bindings by role
    MotionScale motion_scale_;                            // kdop's motion to what the shaders read
    bool reads_depth_ = false;
    std::vector<float> zeros_;  // two per input pixel: the motion, or the depth, where a frame has none
    std::vector<float> scaled_; // the motion converted (motion_scale_)
};

} // namespace kdop
