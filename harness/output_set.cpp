#include "harness/output_set.h"

#include "core/output_listing.h"
#include "images/image_io.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

namespace kdop {

Result<OutputSet> OutputSet::prepare(const std::filesystem::path& dir, const std::string& option) {
    if (auto ok = check_output_directory(dir, option); !ok) return std::unexpected(ok.error());
    auto listed = read_output_listing(dir);
    if (!listed) return fail(fmt::format("{} {}: {}", option, dir.string(), listed.error().message));
    return OutputSet(dir, std::move(*listed));
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
    namespace fs = std::filesystem;
    std::vector<OutputWriter> writers;
    for (const OutputFile& f : files_) writers.push_back(content_writer(f));
    writers.insert(writers.end(), images_.begin(), images_.end());
    // The listing names every file of the set and goes in place last.
    std::vector<std::string> written;
    for (const OutputWriter& w : writers) written.push_back(w.path.lexically_relative(dir_).generic_string());
    const OutputFile listing{dir_ / kOutputListingName, output_listing_text(written)};
    written.push_back(std::string(kOutputListingName));
    writers.push_back(content_writer(listing));
    const std::vector<fs::path> stale = stale_outputs(dir_, listed_, written);
    if (auto ok = write_atomically(writers, stale); !ok) return ok;
    // The folders the stale files leave empty (a sequence no longer measured), innermost first;
    // one that holds anything else stays.
    for (const fs::path& file : stale)
        for (fs::path folder = file.parent_path(); folder != dir_ && folder.native().size() > dir_.native().size();
             folder = folder.parent_path()) {
            std::error_code not_empty;
            if (!fs::remove(folder, not_empty)) break;
        }
    return {};
}

} // namespace kdop
