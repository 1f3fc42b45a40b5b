// Any frame source written as a sequence (the format of sequence.h): `kdop scene` writes kdop's
// own scenes this way, so a user can look at, edit or replay exactly the frames kdop measures.
#pragma once

#include "core/write_files.h"
#include "sequence/frame_source.h"

#include <memory>
#include <string>
#include <vector>

namespace kdop {

// sequence.json for `source`, naming color/NNNN.exr, motion/NNNN.exr (frames with a history),
// depth/NNNN.exr and reference/NNNN.exr where the source has them; motion in pixels, pointing to
// the previous frame, y down.
std::string sequence_json(const FrameSource& source);

// The writers of every frame's files under `folder` (sequence.json not included), for a set
// written all or nothing (core/write_files.h). Each frame is made when its first file is written
// and dropped after its last, so writing holds one frame in memory, however many there are.
std::vector<OutputWriter> sequence_frame_writers(const std::filesystem::path& folder,
                                                 std::shared_ptr<const FrameSource> source);

} // namespace kdop
