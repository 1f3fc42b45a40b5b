// `kdop scene`'s work after its command line is read: kdop's own scenes written as frame
// sequences (sequence/sequence_writer.h), exactly the frames `kdop taa` measures, or one sequence
// per scene with the motion and jitter asked for.
#pragma once

#include "core/result.h"
#include "harness/output_set.h"
#include "images/image_io.h"
#include "scenes/taa_scene.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace kdop {

// kdop's own sequence format (sequence/sequence_writer.h), or Arm's NSS capture layout
// (sequence/nss_writer.h).
enum class SceneLayout { kdop, nss };

struct SceneExportOptions {
    std::uint32_t frames = 200; // per sequence
    // Neither given: two sequences per scene, <scene>-shimmer (jitter on, still) and
    // <scene>-ghosting (moving, jitter off), as kdop taa measures them. Either: one sequence
    // <scene>, the other on.
    std::optional<bool> animate, jitter;
    SceneLayout layout = SceneLayout::kdop;
    // NSS: the scenes' upscaling ratio (--upscale), which names x{ratio}, and the precision of
    // color, ground truth and motion.
    double ratio = 1;
    FloatPrecision precision = FloatPrecision::half;
};

// Adds every sequence of `scenes` to `outputs` and writes the set, drawing the frames as they are
// written, with a progress line. kdop's layout: one folder per sequence. NSS: `outputs`' folder is
// the dataset's root, the sequences numbered 0000, 0001, ... in the order returned, and
// kdop_sequences.json there names each; a scene that cannot be written so (no references: a 2-D
// scene, or a 3-D one without --reference-samples or --upscale) is refused before anything is
// drawn or written (Error::usage). Returns the sequences' names, in the order written.
Result<std::vector<std::string>> export_scenes(const std::vector<std::shared_ptr<const TaaScene>>& scenes,
                                               const SceneExportOptions& options, OutputSet& outputs);

} // namespace kdop
