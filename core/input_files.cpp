#include "core/input_files.h"

#include <fmt/format.h>

#include <map>
#include <mutex>
#include <sys/stat.h>
#include <utility>

namespace kdop {
namespace fs = std::filesystem;

namespace {

using FileId = std::pair<dev_t, ino_t>;

std::optional<FileId> file_id(const fs::path& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return std::nullopt;
    return FileId{st.st_dev, st.st_ino};
}

struct Inputs {
    std::mutex lock;
    bool on = false;
    std::map<FileId, fs::path> by_id; // the first spelling read
};
Inputs& inputs() {
    static Inputs i;
    return i;
}

} // namespace

std::optional<FileIdentity> file_identity(const fs::path& path) {
    const auto id = file_id(path);
    if (!id) return std::nullopt;
    return FileIdentity{std::uint64_t(id->first), std::uint64_t(id->second)};
}

bool same_file(const fs::path& a, const fs::path& b) {
    const auto id_a = file_id(a);
    return id_a && id_a == file_id(b);
}

void protect_inputs(bool on) {
    std::lock_guard held(inputs().lock);
    inputs().on = on;
    if (!on) inputs().by_id.clear();
}

void note_input(const fs::path& path, const fs::path& shown) {
    std::lock_guard held(inputs().lock);
    if (!inputs().on) return;
    if (const auto id = file_id(path)) inputs().by_id.emplace(*id, shown.empty() ? path : shown);
}

std::optional<fs::path> noted_input_at(const fs::path& output) {
    const auto id = file_id(output);
    if (!id) return std::nullopt;
    std::lock_guard held(inputs().lock);
    const auto found = inputs().by_id.find(*id);
    if (found == inputs().by_id.end()) return std::nullopt;
    return found->second;
}

Result<void> check_not_an_input(const fs::path& output, std::string_view option, std::span<const fs::path> given) {
    std::optional<fs::path> input = noted_input_at(output);
    for (const fs::path& candidate : given)
        if (!input && same_file(output, candidate)) input = candidate;
    if (!input) return {};
    const std::string same =
        input->string() == output.string() ? "" : fmt::format(", the same file as {}", input->string());
    return usage_fail(
        fmt::format("{} {}: is an input of this run{}; kdop never writes over an input, so name another file", option,
                    output.string(), same));
}

Result<void> check_distinct_files(std::span<const std::string> paths, std::string_view option) {
    for (std::size_t i = 0; i < paths.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (paths[i] == paths[j] || same_file(paths[i], paths[j]))
                return fail(paths[i] == paths[j]
                                ? fmt::format("{}: {} is given twice", option, paths[i])
                                : fmt::format("{}: {} is given twice (as {} too)", option, paths[i], paths[j]));
    return {};
}

} // namespace kdop
