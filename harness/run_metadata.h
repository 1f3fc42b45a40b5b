// What every measurement's outputs say about the run that made them: the command as it was typed
// (pasting it reproduces the run), kdop's version and the commit it was built from, when and on
// which machine and device, and the seed. Reports print it as their header; JSON carries it whole.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace kdop {

class Context;

struct RunMetadata {
    std::string version;        // kdop's, e.g. "0.1.0"
    std::string commit;         // git describe of the source tree when kdop was configured; "unknown" outside git
    std::string command;        // the process's argv, shell-quoted
    std::string date;           // UTC, ISO 8601
    std::string machine;        // CPU model and core count
    std::string device, driver; // empty where no device took part
    std::string device_type;    // "cpu", "discrete GPU", "integrated GPU", "virtual GPU" or "other"; as device
    std::optional<std::uint64_t> seed;
    // The resolve the figures come from, where not kdop's own: a renderer's (kdop taa --resolve),
    // "<file> (fnv1a64 <hash of its text and map>)".
    std::string resolve;
    // Under mpirun, what each rank measured (kdop taa: its sources) and on what device; empty for
    // one rank.
    struct RankShare {
        std::string device;
        double seconds = 0; // measuring its share (and writing its images), before rank 0 gathers
        std::vector<std::string> measured;
    };
    std::vector<RankShare> ranks; // by rank
};

// Keeps argv for describe_run(); main() calls it first.
void record_command_line(int argc, const char* const* argv);

// Everything but the device and the seed, which the command fills in.
RunMetadata describe_run();
// The same, with the device and driver of `context`.
RunMetadata describe_run(const Context& context);

// "- command: `...`\n- kdop: ...\n": the header lines of a Markdown report.
std::string metadata_markdown(const RunMetadata& run);
nlohmann::json metadata_json(const RunMetadata& run);

// `text` quoted for a POSIX shell where it needs to be ("a b" -> 'a b').
std::string shell_quote(const std::string& text);

} // namespace kdop
