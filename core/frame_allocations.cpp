#include "core/frame_allocations.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace kdop {

void reuse_freed_frames() {
#if defined(__GLIBC__)
    // Below the threshold, blocks come from the heap: a 3840x2160 RGBA float frame (133 MB) too.
    constexpr int kHeapBlocksUpTo = 256 << 20;
    // Freed memory at the top of a heap is given back to the system only beyond this.
    constexpr int kKeepFreed = 256 << 20;
    mallopt(M_MMAP_THRESHOLD, kHeapBlocksUpTo);
    mallopt(M_TRIM_THRESHOLD, kKeepFreed);
#endif
}

} // namespace kdop
