#include "harness/run_metadata.h"

#include "core/escaped_text.h"
#include "core/parallel_for.h"
#include "kdop_commit.h"
#include "runtime/context.h"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <fstream>
#include <thread>

#if !defined(KDOP_VERSION) || !defined(KDOP_COMMIT)
#error "KDOP_VERSION and KDOP_COMMIT must be defined by the build"
#endif

namespace kdop {
namespace {

std::string& command_line() {
    static std::string line;
    return line;
}

std::string utc_now_iso8601() {
    return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}",
                       std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now()));
}

// CPU model and core count, from /proc/cpuinfo.
std::string machine_description() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string model = "unknown CPU";
    for (std::string line; std::getline(cpuinfo, line);)
        if (line.starts_with("model name")) {
            model = line.substr(line.find(':') + 2);
            break;
        }
    return fmt::format("{}, {} cores", model, core_count());
}

} // namespace

std::string shell_quote(const std::string& text) {
    const bool plain = !text.empty() && text.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                               "0123456789-_./=:,+@%") == std::string::npos;
    if (plain) return text;
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

void record_command_line(int argc, const char* const* argv) {
    std::string line;
    for (int i = 0; i < argc; ++i) {
        if (i) line += ' ';
        line += shell_quote(argv[i]);
    }
    command_line() = line;
}

RunMetadata describe_run() {
    RunMetadata run;
    run.version = KDOP_VERSION;
    run.commit = KDOP_COMMIT;
    run.command = command_line();
    run.date = utc_now_iso8601();
    run.machine = machine_description();
    return run;
}

RunMetadata describe_run(const Context& context) {
    RunMetadata run = describe_run();
    run.device = context.device_name();
    run.driver = context.driver_info();
    switch (context.properties().deviceType) {
    case VK_PHYSICAL_DEVICE_TYPE_CPU: run.device_type = "cpu"; break;
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: run.device_type = "discrete GPU"; break;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: run.device_type = "integrated GPU"; break;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: run.device_type = "virtual GPU"; break;
    default: run.device_type = "other"; break;
    }
    return run;
}

std::string metadata_markdown(const RunMetadata& run) {
    std::string out = fmt::format("- command: {}\n- kdop: {} (commit {})\n- date: {}\n- machine: {}\n",
                                  markdown_code(run.command), run.version, run.commit, run.date, run.machine);
    if (!run.device.empty()) out += fmt::format("- device: {} ({}; {})\n", run.device, run.device_type, run.driver);
    if (run.seed) out += fmt::format("- seed: {}\n", *run.seed);
    if (!run.resolve.empty()) out += fmt::format("- resolve: {}\n", markdown_code(run.resolve));
    if (!run.ranks.empty()) out += fmt::format("- ranks: {} (MPI), each measuring:\n", run.ranks.size());
    for (std::size_t r = 0; r < run.ranks.size(); ++r) {
        std::vector<std::string> measured;
        for (const std::string& name : run.ranks[r].measured) measured.push_back(markdown_text(name));
        out += fmt::format("  - rank {} on {}, {:.1f} s: {}\n", r, markdown_text(run.ranks[r].device),
                           run.ranks[r].seconds,
                           measured.empty() ? "nothing" : fmt::format("{}", fmt::join(measured, ", ")));
    }
    return out;
}

nlohmann::json metadata_json(const RunMetadata& run) {
    nlohmann::json j = {{"command", run.command},
                        {"kdop_version", run.version},
                        {"commit", run.commit},
                        {"date", run.date},
                        {"machine", run.machine}};
    j["device"] = run.device.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.device);
    j["driver"] = run.driver.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.driver);
    j["device_type"] = run.device_type.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.device_type);
    j["seed"] = run.seed ? nlohmann::json(*run.seed) : nlohmann::json(nullptr);
    if (!run.resolve.empty()) j["resolve"] = run.resolve;
    for (const RunMetadata::RankShare& share : run.ranks)
        j["ranks"].push_back({{"device", share.device}, {"seconds", share.seconds}, {"measured", share.measured}});
    return j;
}

} // namespace kdop
