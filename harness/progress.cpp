#include "harness/progress.h"

#include "core/shown_text.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <unistd.h>

namespace kdop {

std::string clock_text(double seconds) {
    const long s = std::lround(std::max(seconds, 0.0));
    if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
    return fmt::format("{}:{:02}", s / 60, s % 60);
}

Progress::Progress(std::string step, std::size_t total, std::string unit)
    : step_(std::move(step)), unit_(std::move(unit)), total_(total), terminal_(isatty(fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()) {}

void Progress::finish() {
    if (finished_) return;
    finished_ = true;
    if (terminal_ && done_ > 0) fmt::print(stderr, "\r\033[K");
    std::fflush(stderr);
}

void Progress::advance(const std::string& item, std::size_t steps) {
    if (steps == 0) return;
    done_ += steps;
    const std::size_t tenth = total_ ? done_ * 10 / total_ : 0;
    if (!terminal_ && item == last_item_ && tenth == last_tenth_ && done_ < total_) return;
    last_item_ = item;
    last_tenth_ = tenth;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const std::string eta =
        done_ < total_ ? fmt::format(", about {} left", clock_text(elapsed / double(done_) * double(total_ - done_)))
                       : "";
    const std::string rate =
        unit_.empty() || elapsed <= 0 ? "" : fmt::format(", {:.1f} {}/s", double(done_) / elapsed, unit_);
    const int width = static_cast<int>(fmt::format("{}", total_).size());
    // One line a step, whatever the names in it hold (one_line_text): a log reads one line per step.
    fmt::print(stderr, "{}[{:>{}}/{}] {} {}  {} elapsed{}{}{}", terminal_ ? "\r\033[K" : "", done_, width, total_,
               one_line_text(step_), one_line_text(item), clock_text(elapsed), rate, eta, terminal_ ? "" : "\n");
    std::fflush(stderr);
}

} // namespace kdop
