// Refusing work whose memory would not fit, up front and with the estimate, instead of being
// killed by the kernel halfway through a run. Estimates are of the large buffers only (images,
// textures, staging), which dominate at the sizes where this matters.
#pragma once

#include "core/result.h"

#include <cstdint>
#include <string>

namespace kdop {

// Bytes this process could still allocate without swapping: the kernel's MemAvailable, or less
// where its cgroup's memory.max or its own limits (`ulimit -v`, `ulimit -d`) say so; 0 where
// unknown, and then nothing is refused.
std::uint64_t available_memory();

// Fails, naming `what` and both figures, when `bytes` exceed available_memory().
Result<void> check_memory(const std::string& what, std::uint64_t bytes);

// Makes glibc give every block of 4 MiB or more back to the system when it is freed (a mapping
// of its own), for the whole process: a program's first call, from main, before any thread starts.
// Otherwise glibc raises that threshold to each freed block's size (up to 32 MiB), so 1920x1080
// float frames (31.6 MiB) come from its heaps, one per thread that allocates, and what they free is
// kept: a 1080p sequence of 4 variants peaked at 1,440 MiB, and at 1,279 with this. It sets up the
// process; a program that embeds kdop's libraries keeps its own allocator's settings.
void return_large_blocks_when_freed();

// Bytes one RGBA float image of width x height takes.
inline std::uint64_t image_bytes(std::uint32_t width, std::uint32_t height) {
    return std::uint64_t(width) * height * 16;
}

// A rectification on the device (lavapipe's device memory is this process's memory): the two
// input images on the host (2), three rgba32f textures (3), the upload buffer for both inputs (2)
// and the read-back buffer (1).
inline std::uint64_t rectify_pass_bytes(std::uint32_t width, std::uint32_t height) {
    return image_bytes(width, height) * 8;
}

} // namespace kdop
