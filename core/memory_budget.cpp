#include "memory_budget.h"

#include <fmt/format.h>

#include <fstream>
#include <string>

namespace kdop {

std::uint64_t available_memory() {
    std::ifstream meminfo("/proc/meminfo");
    for (std::string key; meminfo >> key;) {
        std::uint64_t kib = 0;
        meminfo >> kib;
        if (key == "MemAvailable:") return kib * 1024;
        meminfo.ignore(64, '\n');
    }
    return 0;
}

Result<void> check_memory(const std::string& what, std::uint64_t bytes) {
    const std::uint64_t available = available_memory();
    if (available == 0 || bytes <= available) return {};
    return fail(fmt::format("{}: needs about {:.1f} GiB of memory, {:.1f} GiB are available", what,
                            double(bytes) / (1ull << 30), double(available) / (1ull << 30)));
}

} // namespace kdop
