// A testbed scene as a frame source (sequence/frame_source.h): each frame drawn on the device
// when the resolve or the sequence writer asks for it, so `kdop taa` measures and `kdop scene`
// writes exactly the same frames.
#pragma once

#include "sequence/frame_source.h"
#include "testbed/device_frames.h"
#include "testbed/testbed_renderer.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace kdop {

struct Scene3dTimeline {
    std::size_t frames = 0;
    bool animate = true;                 // the figure or car moves; else it stays as at time 0
    bool jitter = false;                 // samples at the R2 jitter; else at the pixel centers
    bool pan = false;                    // the camera slides sideways (camera_at)
    std::uint32_t reference_samples = 0; // > 0: each frame has a reference, the mean of this many
                                         // samples per pixel at the first R2 points
    // > 1: frames drawn for temporal upscaling by this ratio, always jittered (Halton 2, 3 over
    // upscale_jitter_phases), their references at the output size.
    double upscale = 1;
};

class Scene3dFrames final : public FrameSource, public DeviceFrames {
public:
    // `renderer` is shared: the sources of one scene draw on one pass, one frame at a time.
    // `reference_renderer` draws the references, at the output size: `renderer` itself but for an
    // upscaling timeline.
    Scene3dFrames(std::string name, std::shared_ptr<TestbedRenderer> renderer,
                  std::shared_ptr<TestbedRenderer> reference_renderer, const Scene3dTimeline& timeline)
        : name_(std::move(name)), renderer_(std::move(renderer)), reference_renderer_(std::move(reference_renderer)),
          timeline_(timeline) {}
    // Frames and references drawn by one renderer, at one size.
    Scene3dFrames(std::string name, std::shared_ptr<TestbedRenderer> renderer, const Scene3dTimeline& timeline)
        : Scene3dFrames(std::move(name), renderer, renderer, timeline) {}

    // The animation time of frame `index`: the index, or 0 without animation.
    double time(std::size_t index) const { return timeline_.animate ? double(index) : 0.0; }
    Camera3d camera(std::size_t index) const;

    const std::string& name() const override { return name_; }
    std::uint32_t width() const override { return reference_renderer_->width(); }
    std::uint32_t height() const override { return reference_renderer_->height(); }
    std::uint32_t input_width() const override { return renderer_->width(); }
    std::uint32_t input_height() const override { return renderer_->height(); }
    std::size_t frame_count() const override { return timeline_.frames; }
    ColorRange color_range() const override { return ColorRange::ldr; }
    bool starts_history(std::size_t index) const override { return index == 0; }
    std::optional<glm::vec2> jitter(std::size_t index) const override;
    bool has_depth() const override { return true; }
    bool has_reference() const override { return timeline_.reference_samples > 0; }
    Result<LoadedFrame> frame(std::size_t index) const override;
    // Drawn by the reference renderer (the output size) at the pixels' centers.
    bool has_output_motion() const override { return true; }
    Result<std::vector<glm::vec2>> output_motion(std::size_t index) const override;
    std::optional<FrameCamera> camera_of(std::size_t index) const override;
    std::string frame_label(std::size_t index) const override;
    const DeviceFrames* device_frames() const override { return this; }
    // The frame's color, motion and depth on the device; its reference is drawn only when read back.
    Result<LoadedFrame> draw_into(std::size_t index, const RasterTargets& targets, bool read_back) const override;

private:
    // The instant and camera frame `index`'s motion points back to: the frame before (frame 0's to
    // the instant before it, which a frame without a history ignores).
    double previous_time(std::size_t index) const { return timeline_.animate ? double(index) - 1.0 : 0.0; }
    Camera3d previous_camera(std::size_t index) const;
    // Frame `index`'s reference: the mean of the samples at the first R2 points, box-filtered.
    Result<Image> reference(std::size_t index) const;
    // Whether every frame shows the same instant from the same place: then one reference serves all.
    bool still() const { return !timeline_.animate && !timeline_.pan; }

    std::string name_;
    std::shared_ptr<TestbedRenderer> renderer_, reference_renderer_;
    Scene3dTimeline timeline_;
    // A still timeline's one reference, drawn when first asked for (frames are drawn on one thread:
    // the source does not read ahead).
    mutable std::optional<Image> still_reference_;
};

} // namespace kdop
