#include "core/memory_budget.h"

#include <fmt/format.h>
#include <malloc.h>

#include <algorithm>
#include <fstream>
#include <string>

namespace kdop {

namespace {

// The kernel's MemAvailable, in bytes; 0 if unknown.
std::uint64_t system_available() {
    std::ifstream meminfo("/proc/meminfo");
    for (std::string key; meminfo >> key;) {
        std::uint64_t kib = 0;
        meminfo >> kib;
        if (key == "MemAvailable:") return kib * 1024;
        meminfo.ignore(64, '\n');
    }
    return 0;
}

// What this process's cgroup (v2) still allows, in bytes; 0 where there is no limit or no cgroup.
std::uint64_t cgroup_available() {
    std::ifstream max_file("/sys/fs/cgroup/memory.max"), current_file("/sys/fs/cgroup/memory.current");
    std::string max;
    std::uint64_t current = 0;
    if (!(max_file >> max) || max == "max" || !(current_file >> current)) return 0;
    const std::uint64_t limit = std::stoull(max);
    return limit > current ? limit - current : 1;
}

} // namespace

std::uint64_t available_memory() {
    // In a container the cgroup's limit, not the host's free memory, is what a process may use.
    const std::uint64_t system = system_available(), cgroup = cgroup_available();
    if (system == 0) return cgroup;
    return cgroup == 0 ? system : std::min(system, cgroup);
}

Result<void> check_memory(const std::string& what, std::uint64_t bytes) {
    const std::uint64_t available = available_memory();
    if (available == 0 || bytes <= available) return {};
    return fail(fmt::format("{}: needs about {:.1f} GiB of memory, {:.1f} GiB are available", what,
                            double(bytes) / (1ull << 30), double(available) / (1ull << 30)));
}

void return_large_blocks_when_freed() {
    // Setting the threshold also stops glibc from raising it as blocks are freed.
    mallopt(M_MMAP_THRESHOLD, 4 << 20);
}

} // namespace kdop
