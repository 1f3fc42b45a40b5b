// kdop's 2-D scenes (taa_scene.h): a background image under two moving objects (a red box and a
// dark ellipse); this file says where they are on each frame, where the camera's sample falls in
// each pixel, and draws the frames a renderer would give the resolve (color, motion, depth), in
// memory, as a frame source (sequence/frame_source.h) that `kdop taa` measures and `kdop scene`
// writes.
//
// The picture: the background repeated and minified by 1.25 texels per pixel, bilinear, without
// mipmaps (so its detail aliases and shimmers under jitter, as distant grass does), under two
// objects with hard, point-sampled edges: a saturated red box (the paper's red car), rotated by
// 0.2 rad so its edges alias on every row, and a near-black ellipse (a shadow or a tire, the
// paper's limitations case). One sample per pixel, at the pixel center plus the jitter.
//
// Animation: each object swings on a sine path, so it never jumps (a jump would be a disocclusion
// no motion vector describes) and the measured frames see it at every speed from rest to about
// 1.2% (the red box) and 1.9% (the dark ellipse) of the frame's width per frame. Jitter: the R2 sequence (Roberts
// 2018), 10 entries, as in Ikkala et al. 2024, centered on the pixel.
#pragma once

#include "core/result.h"
#include "images/image.h"
#include "images/image_io.h"
#include "scenes/taa_scene.h"
#include "sequence/frame_source.h"
#include "sequence/jitter.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace kdop {

// A background under the two objects.
class SpriteScene final : public TaaScene {
public:
    // `background`: linear RGB in [0, 1], of the frame's size; repeated and minified by the shader.
    SpriteScene(std::string name, Image background) : name_(std::move(name)), background_(std::move(background)) {}
    const Image& background() const { return background_; }

    const std::string& name() const override { return name_; }
    std::uint32_t width() const override { return background_.width; }
    std::uint32_t height() const override { return background_.height; }
    std::string content() const override;
    std::shared_ptr<const FrameSource> frames(const std::string& name, std::size_t count, bool animate,
                                              bool jitter) const override;
    // Where the red box moves fastest, and half the frame around it, shifted toward where it came
    // from, so its trail is in view.
    std::uint32_t trail_frame(const TaaSchedule& schedule) const override;
    TrailCrop trail_crop(const TaaSchedule& schedule) const override;

private:
    std::string name_;
    Image background_;
};

// The paper's two backgrounds as kdop's synthetic families ("grass": high-frequency chroma and
// luma; "asphalt": high-frequency luma), then the first installed real texture, if any.
std::vector<SpriteScene> default_sprite_scenes(std::uint32_t width, std::uint32_t height, std::uint64_t seed);
// Their names, without drawing or reading anything.
std::vector<std::string> sprite_scene_names();

// A user's background: its top-left corner of the frame's size read (images/image_io.h,
// read_image_corner: no more of a larger image is decoded), then tiled to the frame. The error
// names the file; values must lie in [0, 1] (the metric is LDR-FLIP), and one that does not is
// named with its pixel.
Result<SpriteScene> read_sprite_scene(const std::string& path, std::uint32_t width, std::uint32_t height,
                                      InputSpace space = InputSpace::from_file);

struct FrameState {
    glm::vec2 jitter{0};                    // sample offset from the pixel center, pixels
    glm::vec2 car_center{0}, car_motion{0}; // pixels; motion since the previous frame
    glm::vec2 shadow_center{0}, shadow_motion{0};
};

// Frame `frame` of a sequence of frames `width` x `height`. Without `animate` the objects stay
// where they are on frame 0 and do not move; without `jitter` every sample is at the pixel center.
FrameState frame_state(std::uint32_t frame, std::uint32_t width, std::uint32_t height, bool animate, bool jitter);

// The frame at `state`: color at each pixel's sample; motion of the surface seen there, pointing
// to where it was last frame; depth 0.5 on the box, 1 on the ground (the ellipse lies on it).
LoadedFrame render_scene(const Image& background, const FrameState& state);

// Frames 0 to `count` - 1 of `scene`, as frame_state() places them.
class SceneFrames final : public FrameSource {
public:
    SceneFrames(std::string name, Image background, std::size_t count, bool animate, bool jitter)
        : name_(std::move(name)), background_(std::move(background)), count_(count), animate_(animate),
          jitter_(jitter) {}
    FrameState state(std::size_t index) const;

    const std::string& name() const override { return name_; }
    std::uint32_t width() const override { return background_.width; }
    std::uint32_t height() const override { return background_.height; }
    std::size_t frame_count() const override { return count_; }
    ColorRange color_range() const override { return ColorRange::ldr; }
    bool starts_history(std::size_t index) const override { return index == 0; }
    std::optional<glm::vec2> jitter(std::size_t index) const override;
    bool has_depth() const override { return true; }
    bool has_reference() const override { return false; }
    Result<LoadedFrame> frame(std::size_t index) const override { return render_scene(background_, state(index)); }
    std::string frame_label(std::size_t index) const override;

private:
    std::string name_;
    Image background_;
    std::size_t count_;
    bool animate_, jitter_;
};

} // namespace kdop
