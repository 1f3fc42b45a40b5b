// How the process allocates frames: one call at the start of main.
#pragma once

namespace kdop {

// Has glibc serve large blocks (frames) from its heap and keep up to 256 MiB of freed memory there,
// instead of mapping each block fresh and unmapping it when freed. A 1920x1080 RGBA float frame is
// 33 MB, just above glibc's largest automatic mapping threshold (32 MiB), so each one a pass
// allocated (a read-back, a staged or decoded frame, a picture) was a fresh mapping: zero-filled
// by the kernel page by page, and given back at once. That was a quarter of a 1080p `kdop taa` run's
// wall time (measured in docs/results.md, "Frames from the heap"). The cost is freed memory the
// process keeps for reuse: up to the trim threshold per arena. Call it first in main, before any
// thread allocates. A no-op where malloc is not glibc's (a sanitizer's).
void reuse_freed_frames();

} // namespace kdop
