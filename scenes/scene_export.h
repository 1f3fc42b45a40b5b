// `kdop scene`'s work after its command line is read: kdop's own scenes written as frame
// sequences (sequence/sequence_writer.h), exactly the frames `kdop taa` measures, or one sequence
// per scene with the motion and jitter asked for.
#pragma once

#include "core/result.h"
#include "harness/output_set.h"
#include "scenes/taa_scene.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace kdop {

struct SceneExportOptions {
    std::uint32_t frames = 200; // per sequence
    // Neither given: two sequences per scene, <scene>-shimmer (jitter on, still) and
    // <scene>-ghosting (moving, jitter off), as kdop taa measures them. Either: one sequence
    // <scene>, the other on.
    std::optional<bool> animate, jitter;
};

// Adds every sequence of `scenes` to `outputs` (one folder each) and writes the set, drawing the
// frames as they are written, with a progress line. Returns how many sequences were written.
Result<std::size_t> export_scenes(const std::vector<std::shared_ptr<const TaaScene>>& scenes,
                                  const SceneExportOptions& options, OutputSet& outputs);

} // namespace kdop
