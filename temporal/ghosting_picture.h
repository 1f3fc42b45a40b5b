// What `kdop taa` shows of a scene's ghosting: the frames at the scene's trail frame and the labeled
// picture of every variant's frame over its FLIP map (trail_picture.h).
#pragma once

#include "core/result.h"
#include "core/variant_key.h"
#include "flip/flip.h"
#include "harness/output_set.h"
#include "images/image.h"
#include "scenes/taa_scene.h"

#include <memory>
#include <string>
#include <vector>

namespace kdop {

// ghosting-<scene>.png
std::string ghosting_picture_name(const std::string& scene);

// What a scene shows of its ghosting, added to `outputs`: the truth (the aliased frame, or the
// reference where the scene has one) and each variant's frame at the trail frame under
// frames/<scene>/, as data (EXR) and to look at (PNG), and the labeled picture of them all, each
// variant's crop over its FLIP map against the truth, under it the variant's ghosting (the mean
// over the measured frames) and this frame's mean FLIP, and the maps' color scale under the grid.
Result<void> add_ghosting_picture(OutputSet& outputs, const TaaScene& scene, const std::string& truth_name,
                                  std::shared_ptr<const Image> truth, const std::vector<VariantKey>& keys,
                                  const std::vector<std::shared_ptr<const Image>>& trails,
                                  const std::vector<double>& ghosting, const LdrFlip& flip,
                                  const TaaSchedule& schedule);

} // namespace kdop
