// Where the TAA resolve's frames come from: a sequence on disk (SequenceFrames below), kdop's own
// scenes rendered in memory (scenes/sprite_scene.h), a 3-D testbed. The resolve, the measurement
// and `kdop scene`'s writer take any of them through this interface, so every source is measured
// the same way and every source can be written as a sequence.
#pragma once

#include "sequence/sequence.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace kdop {

class DeviceFrames; // testbed/device_frames.h

// The camera a frame was drawn with, where the source has one (kdop's 3-D testbed): what an NSS
// capture's per-frame metadata records.
struct FrameCamera {
    float fov_x = 0, fov_y = 0;          // radians, at the output's aspect
    float near_plane = 0, far_plane = 0; // in the scene's units
    // World to clip, for column vectors (clip = M p), without jitter, at the output size.
    glm::mat4 view_projection{1.0f};
};

class FrameSource {
public:
    virtual ~FrameSource() = default;
    virtual const std::string& name() const = 0;
    // The size the resolve outputs at, and the reference has (and, but for an upscaling source,
    // the frames' color, motion and depth).
    virtual std::uint32_t width() const = 0;
    virtual std::uint32_t height() const = 0;
    // The size of the frames' color, motion and depth: smaller than width() x height() for a source
    // rendered for temporal upscaling (docs/taa.md, "Upscaling"), whose reference is at the output size.
    virtual std::uint32_t input_width() const { return width(); }
    virtual std::uint32_t input_height() const { return height(); }
    bool upscales() const { return input_width() != width() || input_height() != height(); }
    virtual std::size_t frame_count() const = 0;
    // The range the frames' color and reference keep to, and so the FLIP they are measured in.
    virtual ColorRange color_range() const = 0;
    // Whether frame `index` starts without a history: the first frame and every camera cut.
    virtual bool starts_history(std::size_t index) const = 0;
    virtual std::optional<glm::vec2> jitter(std::size_t index) const = 0;
    // Whether every frame has a depth image, or a reference image.
    virtual bool has_depth() const = 0;
    virtual bool has_reference() const = 0;
    // Frame `index`'s images, motion in load_frame()'s convention.
    virtual Result<LoadedFrame> frame(std::size_t index) const = 0;
    // Whether the source can give each frame's motion at the output size, drawn at the output
    // pixels' centers without jitter (what an NSS capture's motion_gt holds), and that motion, in
    // load_frame()'s convention, row-major, width() x height(). A source that draws its frames
    // (the 3-D testbed) draws it; others have none.
    virtual bool has_output_motion() const { return false; }
    virtual Result<std::vector<glm::vec2>> output_motion(std::size_t index) const;
    // Frame `index`'s camera, where the source draws its frames through one.
    virtual std::optional<FrameCamera> camera_of(std::size_t /*index*/) const { return std::nullopt; }
    // What an error about frame `index`'s color names: its file, or the scene and frame.
    virtual std::string frame_label(std::size_t index) const = 0;
    // Whether frame() may run on another thread while the resolve works on the last frame (it
    // reads files and shares nothing), so the measurement reads frames ahead. Not a source that
    // draws on the device, whose queue the resolve uses.
    virtual bool reads_ahead() const { return false; }
    // The figures the source is meant for (sequence.json's "measure"): both unless it says.
    virtual SequenceRoles roles() const { return {}; }
    // Where the source draws its frames on the device, what draws one straight into a resolve's
    // inputs, bringing back only what the host reads of it; else null.
    virtual const DeviceFrames* device_frames() const { return nullptr; }
};

// `source` meant for `roles` alone: kdop's scenes' still sequence is measured for shimmer and their
// moving one for ghosting. Everything else is the source's.
class MeasuredFor final : public FrameSource {
public:
    MeasuredFor(std::shared_ptr<const FrameSource> source, SequenceRoles roles)
        : source_(std::move(source)), roles_(roles) {}
    const std::string& name() const override { return source_->name(); }
    std::uint32_t width() const override { return source_->width(); }
    std::uint32_t height() const override { return source_->height(); }
    std::uint32_t input_width() const override { return source_->input_width(); }
    std::uint32_t input_height() const override { return source_->input_height(); }
    std::size_t frame_count() const override { return source_->frame_count(); }
    ColorRange color_range() const override { return source_->color_range(); }
    bool starts_history(std::size_t index) const override { return source_->starts_history(index); }
    std::optional<glm::vec2> jitter(std::size_t index) const override { return source_->jitter(index); }
    bool has_depth() const override { return source_->has_depth(); }
    bool has_reference() const override { return source_->has_reference(); }
    Result<LoadedFrame> frame(std::size_t index) const override { return source_->frame(index); }
    bool has_output_motion() const override { return source_->has_output_motion(); }
    Result<std::vector<glm::vec2>> output_motion(std::size_t index) const override {
        return source_->output_motion(index);
    }
    std::optional<FrameCamera> camera_of(std::size_t index) const override { return source_->camera_of(index); }
    std::string frame_label(std::size_t index) const override { return source_->frame_label(index); }
    bool reads_ahead() const override { return source_->reads_ahead(); }
    SequenceRoles roles() const override { return roles_; }
    const DeviceFrames* device_frames() const override { return source_->device_frames(); }

private:
    std::shared_ptr<const FrameSource> source_;
    SequenceRoles roles_;
};

// A sequence read from disk, one frame at a time.
class SequenceFrames final : public FrameSource {
public:
    SequenceFrames(Sequence sequence, InputSpace space) : s_(std::move(sequence)), space_(space) {}
    const Sequence& sequence() const { return s_; }
    // The same frames read without their depth files, for a resolve that does not read depth: each
    // frame comes without depth, and the files are neither decoded nor checked.
    SequenceFrames without_depth() const {
        SequenceFrames s = *this;
        s.depth_ = false;
        return s;
    }

    const std::string& name() const override { return s_.name; }
    std::uint32_t width() const override { return s_.upscales() ? s_.output_width : s_.width; }
    std::uint32_t height() const override { return s_.upscales() ? s_.output_height : s_.height; }
    std::uint32_t input_width() const override { return s_.width; }
    std::uint32_t input_height() const override { return s_.height; }
    std::size_t frame_count() const override { return s_.frames.size(); }
    ColorRange color_range() const override { return s_.color_range; }
    bool starts_history(std::size_t index) const override { return s_.starts_history(index); }
    std::optional<glm::vec2> jitter(std::size_t index) const override { return s_.frames[index].jitter; }
    bool has_depth() const override;
    bool has_reference() const override;
    Result<LoadedFrame> frame(std::size_t index) const override { return load_frame(s_, index, space_, depth_); }
    std::string frame_label(std::size_t index) const override;
    bool reads_ahead() const override { return true; }
    SequenceRoles roles() const override { return s_.measure; }

private:
    Sequence s_;
    InputSpace space_;
    bool depth_ = true; // whether frames are read with their depth
};

} // namespace kdop
