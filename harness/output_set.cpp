#include "harness/output_set.h"

#include "images/image_io.h"

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
    add(stem + ".json", json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

void OutputSet::add(std::vector<OutputWriter> writers) {
    images_.insert(images_.end(), std::make_move_iterator(writers.begin()), std::make_move_iterator(writers.end()));
}

void OutputSet::add_image(const std::string& name, std::shared_ptr<const Image> image) {
    images_.push_back(image_writer(dir_ / name, std::move(image)));
}

Result<void> OutputSet::write() const {
    std::vector<OutputWriter> writers;
    for (const OutputFile& f : files_) writers.push_back(content_writer(f));
    writers.insert(writers.end(), images_.begin(), images_.end());
    return write_atomically(writers);
}

} // namespace kdop
