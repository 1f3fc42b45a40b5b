// The frame a source's writers are on (sequence_writer.h, nss_writer.h): a frame's files are
// written one after another, each by its own writer, and the frame is made (drawn or read) once,
// by the first of them, kept for the others and dropped when the next frame is made, so writing
// holds one frame in memory however many there are.
#pragma once

#include "sequence/frame_source.h"

#include <cstdint>
#include <memory>

namespace kdop {

struct FrameCache {
    std::shared_ptr<const FrameSource> source;
    std::size_t index = SIZE_MAX;
    LoadedFrame frame;

    Result<const LoadedFrame*> get(std::size_t i) {
        if (i != index) {
            index = SIZE_MAX;
            auto loaded = source->frame(i);
            if (!loaded) return std::unexpected(loaded.error());
            frame = std::move(*loaded);
            index = i;
        }
        return &frame;
    }
};

} // namespace kdop
