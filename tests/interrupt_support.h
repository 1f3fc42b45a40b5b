// Running a real kdop until it holds at a point (KDOP_TEST_HOLD, core/interrupt.h) or ends by
// itself, and ending it with signals: how it ended, and what it left in a folder.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace kdop::test {

struct Ending {
    int exit_code; // -1 when it did not exit by itself
    int signal;    // the signal that ended it, or 0
    std::string err;
};

// Runs `command` (through sh, with `environment` added) until it holds at `point` (by default
// before moving its outputs into place), calls `when_held` (to look at what the run has made so
// far), sends it `signals` there in that order, and returns how it ended.
Ending interrupt_at(const std::string& command, const std::vector<int>& signals, const std::string& environment = "",
                    const std::string& point = "write_atomically", const std::function<void()>& when_held = {});
inline Ending interrupt_at_write(const std::string& command, int signal, const std::string& environment = "",
                                 const std::string& point = "write_atomically") {
    return interrupt_at(command, {signal}, environment, point);
}

// Runs `command` (through sh, with `environment` added) to its end, `prepare` called in the child
// first (to limit it, or to give it other streams).
Ending run_until_it_ends(const std::string& command, const std::string& environment,
                         const std::function<void()>& prepare);

// Every file under `dir` with its bytes: what a run must leave as it was.
std::map<std::string, std::string> snapshot(const std::filesystem::path& dir);

// Whether a temporary of an output set (`*.kdop-partial-*`) is anywhere under `dir`.
bool has_temporaries(const std::filesystem::path& dir);

} // namespace kdop::test
