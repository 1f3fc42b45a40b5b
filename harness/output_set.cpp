#include "output_set.h"

#include <nlohmann/json.hpp>

namespace kdop {

Result<OutputSet> OutputSet::prepare(const std::filesystem::path& dir, const std::string& option) {
    if (auto ok = check_output_directory(dir, option); !ok) return std::unexpected(ok.error());
    return OutputSet(dir);
}

void OutputSet::add(const std::string& name, std::string content) {
    files_.push_back({dir_ / name, std::move(content)});
}

void OutputSet::add(std::vector<OutputFile> files) {
    for (OutputFile& f : files) files_.push_back(std::move(f));
}

void OutputSet::add_table(const std::string& stem, const Table& table, const RunMetadata& run) {
    add(stem + ".csv", table.csv());
    nlohmann::json json = table.json();
    json["run"] = metadata_json(run);
    add(stem + ".json", json.dump(2) + "\n");
}

Result<void> OutputSet::write() const { return write_files_atomically(files_); }

} // namespace kdop
