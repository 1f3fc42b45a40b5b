// What `kdop taa` shows of a scene's or sequence's ghosting: the frames at one frame (a scene's trail
// frame, a sequence's frame where the variants differ most) and the labeled picture of every
// variant's frame over its FLIP map (trail_picture.h).
#pragma once

#include "core/result.h"
#include "core/variant_key.h"
#include "flip/flip.h"
#include "harness/scratch_directory.h"
#include "harness/staged_images.h"
#include "images/image.h"
#include "scenes/taa_scene.h"
#include "temporal/picture_flip.h"
#include "temporal/taa_measure.h"

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace kdop {

// ghosting-<scene>.png
std::string ghosting_picture_name(const std::string& scene);

// The frame a picture shows: the scene's or sequence's name, the frame's index and the part shown.
struct PictureFrame {
    std::string source;
    std::size_t index = 0;
    TrailCrop crop;
};

// A picture's frames, each variant's, brought one at a time (from memory, or read back from where
// they were staged), so a picture of 12 variants at 1080p holds one frame, not 12.
struct PictureFrames {
    std::size_t count = 0;
    std::function<Result<std::shared_ptr<const Image>>(std::size_t v)> frame;
};
// Frames held in memory.
PictureFrames frames_in_memory(std::vector<std::shared_ptr<const Image>> frames);

// Each of `frames`' FLIP map against `truth` (LDR- or HDR-FLIP, as `flip` measures), the truth's
// work kept from one frame to the next: what the picture below shows, and what a sequence's crop
// is chosen by.
Result<std::vector<std::vector<float>>> ghosting_maps(PictureFlip& flip, const Image& truth,
                                                      const PictureFrames& frames);

// What a scene or sequence shows of its ghosting, staged in `outputs` (written now, moved into the
// output folder with the rest): the truth (the aliased frame,
// or the reference where there is one) and each variant's frame at `shown` under frames/<source>/,
// as data (EXR) and to look at (PNG; HDR tone mapped), and the labeled picture of them all, each
// variant's crop over its FLIP map against the truth (`maps`, ghosting_maps' of the frames), under
// it the variant's ghosting (the mean over the measured frames) and this frame's mean FLIP, and
// the maps' color scale under the grid.
Result<void> add_ghosting_picture(StagedImages& outputs, const PictureFrame& shown, const std::string& truth_name,
                                  std::shared_ptr<const Image> truth, const std::vector<VariantKey>& keys,
                                  const PictureFrames& frames, const std::vector<std::vector<float>>& maps,
                                  const std::vector<double>& ghosting, const PictureFlip& flip);

// The frame a sequence's picture shows: `fixed` where given (--picture-frame), else where the
// variants' ghosting differs most (the largest spread, max - min, of their FLIP on the frame; with
// one variant, where it is largest), the earliest of equals. Fed each measured frame as it goes, it
// stages that frame's outputs in a scratch folder (write_raw), not in memory: they are one frame
// per variant, for the length of the pass.
class PictureFrameChooser {
public:
    explicit PictureFrameChooser(std::optional<std::size_t> fixed = std::nullopt) : fixed_(fixed) {}
    // An error where the frame's outputs cannot come to the host.
    Result<void> offer(const MeasuredFrame& frame);
    bool chosen() const { return outputs_ > 0; }
    std::size_t index() const { return index_; }
    // The chosen frame's outputs, read back one at a time; valid while the chooser lives.
    PictureFrames outputs() const;

private:
    std::optional<std::size_t> fixed_;
    std::size_t index_ = 0;
    double spread_ = -1;
    std::size_t outputs_ = 0;
    std::uint32_t width_ = 0, height_ = 0;
    std::unique_ptr<ScratchDirectory> scratch_; // made when the first frame is kept
};

// A crop of at most 320x180 of width x height frames, centered where the variants' `maps` (FLIP per
// pixel) differ most (with one variant, where its FLIP is largest), kept inside the frame, and
// magnified up to 4 times so that it is at least 240 pixels wide.
TrailCrop disagreement_crop(const std::vector<std::vector<float>>& maps, std::uint32_t width, std::uint32_t height);

} // namespace kdop
