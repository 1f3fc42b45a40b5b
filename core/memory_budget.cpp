#include "core/memory_budget.h"

#include <fmt/format.h>
#include <malloc.h>
#include <sys/resource.h>

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

// The bytes of `key` ("VmSize:") in /proc/self/status; 0 if unknown.
std::uint64_t own_status_bytes(const std::string& key) {
    std::ifstream status("/proc/self/status");
    for (std::string name; status >> name;) {
        if (name == key) {
            std::uint64_t kib = 0;
            status >> kib;
            return kib * 1024;
        }
        status.ignore(1 << 20, '\n');
    }
    return 0;
}

// What `resource` (RLIMIT_AS, `ulimit -v`; RLIMIT_DATA, `ulimit -d`) still lets this process map
// beyond the `used` bytes it has mapped (its VmSize, VmData); 0 where there is no limit. A large
// allocation past it fails however much memory the system has free: a std::bad_alloc in the
// middle of a read, not the refusal up front with the memory needed.
std::uint64_t limit_available(int resource, const char* used_key) {
    rlimit limit{};
    if (getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 0;
    const std::uint64_t used = own_status_bytes(used_key);
    return limit.rlim_cur > used ? limit.rlim_cur - used : 1;
}

} // namespace

std::uint64_t available_memory() {
    // In a container the cgroup's limit, not the host's free memory, is what a process may use;
    // under `ulimit -v` or `-d`, what is left of the limit.
    std::uint64_t available = 0;
    for (const std::uint64_t bound : {system_available(), cgroup_available(), limit_available(RLIMIT_AS, "VmSize:"),
                                      limit_available(RLIMIT_DATA, "VmData:")})
        if (bound != 0) available = available == 0 ? bound : std::min(available, bound);
    return available;
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
