#include "progress.h"

#include <fmt/format.h>

#include <cstdio>
#include <unistd.h>

namespace kdop::bench {

Progress::Progress(std::string step, std::size_t total)
    : step_(std::move(step)), total_(total), terminal_(isatty(fileno(stderr)) != 0) {}

Progress::~Progress() {
    if (terminal_ && done_ > 0) fmt::print(stderr, "\n");
}

void Progress::advance(const std::string& item) {
    ++done_;
    const int width = static_cast<int>(fmt::format("{}", total_).size());
    fmt::print(stderr, "{}[{:>{}}/{}] {} {}{}", terminal_ ? "\r\033[K" : "", done_, width, total_, step_, item,
               terminal_ ? "" : "\n");
    std::fflush(stderr);
}

} // namespace kdop::bench
