// A 3-D testbed scene (testbed/scene3d.h: grass3d, asphalt3d) as a scene `kdop taa` measures and
// `kdop scene` writes: its frames drawn on the device, one renderer shared by its sequences.
#pragma once

#include "scenes/taa_scene.h"
#include "testbed/scene3d.h"
#include "testbed/testbed_renderer.h"

#include <memory>

namespace kdop {

class TestbedScene final : public TaaScene {
public:
    // With `camera_pan`, every sequence's camera slides sideways; with `reference_samples` > 0,
    // every frame has a reference of that many samples per pixel. With `upscale` > 1 the frames are
    // drawn at width / upscale x height / upscale (rounded, at least 1), jittered, for a resolve to
    // upscale to width x height, the references' size; they need reference_samples > 0.
    static Result<std::shared_ptr<TestbedScene>> create(const Context& context, Scene3d scene, std::uint32_t width,
                                                        std::uint32_t height, bool camera_pan,
                                                        std::uint32_t reference_samples, double upscale = 1);

    const std::string& name() const override { return renderer_->scene().name; }
    std::uint32_t width() const override { return reference_renderer_->width(); }
    std::uint32_t height() const override { return reference_renderer_->height(); }
    std::string content() const override;
    std::shared_ptr<const FrameSource> frames(const std::string& name, std::size_t count, bool animate,
                                              bool jitter) const override;
    // Where the moving mesh's vertices move most on the screen, and half the frame around the
    // mesh, shifted toward where it came from, so its trail is in view.
    std::uint32_t trail_frame(const TaaSchedule& schedule) const override;
    TrailCrop trail_crop(const TaaSchedule& schedule) const override;

private:
    TestbedScene(std::shared_ptr<TestbedRenderer> renderer, std::shared_ptr<TestbedRenderer> reference_renderer,
                 bool camera_pan, std::uint32_t reference_samples, double upscale)
        : renderer_(std::move(renderer)), reference_renderer_(std::move(reference_renderer)), camera_pan_(camera_pan),
          reference_samples_(reference_samples), upscale_(upscale) {}
    // The moving mesh on the screen at `time`, in pixels: its bounding box, its vertices' mean
    // motion since the frame before, and the mean of their positions weighted by how far each
    // moved (where the motion is: a kicking leg rather than the figure's middle).
    struct OnScreen {
        glm::vec2 low{0}, high{0}, motion{0}, moving_center{0};
    };
    OnScreen on_screen(double time) const;

    std::shared_ptr<TestbedRenderer> renderer_, reference_renderer_; // the frames', the references'
    bool camera_pan_;
    std::uint32_t reference_samples_;
    double upscale_;
};

} // namespace kdop
