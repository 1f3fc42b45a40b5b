#include "run_info.h"

#include "subprocess.h"

#include <fmt/chrono.h>
#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#ifndef KDOP_SOURCE_DIR
#error "KDOP_SOURCE_DIR must be defined by the build"
#endif

namespace kdop::bench {
namespace {

// The first line git prints for `args`, or empty if it fails.
std::string git_output(const std::vector<std::string>& args, const std::filesystem::path& log) {
    const std::filesystem::path git = find_program("git");
    if (git.empty()) return {};
    std::vector<std::string> argv{git.string(), "-C", KDOP_SOURCE_DIR};
    argv.insert(argv.end(), args.begin(), args.end());
    auto status = run_program(argv, log);
    if (!status || *status != 0) return {};
    std::ifstream in(log);
    std::string line;
    std::getline(in, line);
    return line;
}

} // namespace

std::string utc_now_iso8601() {
    return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now()));
}

std::string machine_description() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string model = "unknown CPU";
    for (std::string line; std::getline(cpuinfo, line);)
        if (line.starts_with("model name")) {
            model = line.substr(line.find(':') + 2);
            break;
        }
    return fmt::format("{}, {} cores", model, std::thread::hardware_concurrency());
}

std::string source_commit() {
    const std::filesystem::path log = std::filesystem::temp_directory_path() / fmt::format("kdop-git-{}.log", getpid());
    std::string commit = git_output({"rev-parse", "--short=12", "HEAD"}, log);
    if (!commit.empty() && !git_output({"status", "--porcelain", "--untracked-files=no"}, log).empty()) commit += "-dirty";
    std::filesystem::remove(log);
    return commit.empty() ? "unknown" : commit;
}

} // namespace kdop::bench
