// Refusing work whose memory would not fit, up front and with the estimate, instead of being
// killed by the kernel halfway through a run. Estimates are of the large buffers only (images,
// textures, staging), which dominate at the sizes where this matters.
#pragma once

#include "core/result.h"

#include <cstdint>
#include <string>

namespace kdop {

// Bytes this process could still allocate without swapping: the kernel's MemAvailable, or less
// where its cgroup's memory.max says so; 0 where unknown, and then nothing is refused.
std::uint64_t available_memory();

// Fails, naming `what` and both figures, when `bytes` exceed available_memory().
Result<void> check_memory(const std::string& what, std::uint64_t bytes);

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
