// A command's outputs: the directory is checked before any work starts (so a bad --out fails at
// once, not after a ten-minute run), files, tables and images are collected as the run goes, and
// all of them are written together at the end, all or nothing (core/write_files.h). Tables are
// written as <stem>.csv and as <stem>.json, the JSON carrying the run's metadata and the columns'
// units; images through OpenImageIO (images/image_io.h), in the format their extension names.
//
// The folder holds one run's outputs: what an earlier kdop run wrote there and this one does not is
// removed with the new set, as part of it (core/output_listing.h), and the folders that leaves
// empty go too.
#pragma once

#include "core/result.h"
#include "core/write_files.h"
#include "harness/run_metadata.h"
#include "harness/table.h"
#include "images/image.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace kdop {

class OutputSet {
public:
    // Fails, naming `option`, when `dir` cannot be written, or naming its listing where that is damaged.
    static Result<OutputSet> prepare(const std::filesystem::path& dir, const std::string& option = "--out");

    const std::filesystem::path& dir() const { return dir_; }
    void add(const std::string& name, std::string content);
    void add(std::vector<OutputFile> files); // paths already in dir(), e.g. drawn charts
    // Files another writer makes when the set is written (paths in dir()), e.g. a sequence's frames.
    void add(std::vector<OutputWriter> writers);
    void add_table(const std::string& stem, const Table& table, const RunMetadata& run);
    // An image at `name` in dir() (subfolders allowed); several names may share one image.
    void add_image(const std::string& name, std::shared_ptr<const Image> image);
    std::size_t size() const { return files_.size() + images_.size(); }

    Result<void> write() const;

private:
    OutputSet(std::filesystem::path dir, std::vector<std::string> listed)
        : dir_(std::move(dir)), listed_(std::move(listed)) {}
    std::filesystem::path dir_;
    std::vector<std::string> listed_; // what the folder's listing said an earlier run wrote
    std::vector<OutputFile> files_;
    std::vector<OutputWriter> images_;
};

} // namespace kdop
