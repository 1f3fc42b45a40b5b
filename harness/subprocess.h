// Running the two programs the bench needs (valgrind, gnuplot), which have no library interface.
#pragma once

#include "core/result.h"

#include <filesystem>
#include <string>
#include <vector>

namespace kdop {

// The path of `name` in PATH, or empty.
std::filesystem::path find_program(const std::string& name);

// Runs argv[0] (a path) with `environment` ("NAME=value") added to this process's environment,
// its stdout and stderr to `log`; returns its exit status (128 + signal if it was killed).
Result<int> run_program(const std::vector<std::string>& argv, const std::filesystem::path& log,
                        const std::vector<std::string>& environment = {});

// The last `count` lines of a log, indented, for an error message.
std::string log_tail(const std::filesystem::path& log, int count);

} // namespace kdop
