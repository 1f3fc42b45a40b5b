// Images a long run produces frame by frame (`kdop taa --write-frames`: every output of every
// variant): each is written to a scratch folder when it is made, so the run holds none of them in
// memory, and joins the run's output set (output_set.h) as a writer that moves it into place with
// the rest, all or nothing. An interrupted or failed run leaves none of them behind.
#pragma once

#include "core/result.h"
#include "core/write_files.h"
#include "harness/scratch_directory.h"
#include "images/image.h"

#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace kdop {

class StagedImages {
public:
    StagedImages() : scratch_(std::make_unique<ScratchDirectory>("kdop-frames")) {}

    // Writes `image` now, to be `name` (relative to the output folder) when the set is written.
    // Several threads may add at once.
    Result<void> add(const std::string& name, const Image& image);
    // A file already encoded (a rank's image, sent to rank 0), to be `name` as above.
    Result<void> add_encoded(const std::string& name, const std::string& bytes);
    // The names added so far, in order, and a staged file's bytes.
    const std::vector<std::string>& names() const { return names_; }
    Result<std::string> bytes(const std::string& name) const;
    // The writers that move the staged images into `dir`; valid while this object lives.
    std::vector<OutputWriter> writers(const std::filesystem::path& dir) const;

private:
    std::unique_ptr<ScratchDirectory> scratch_;
    std::mutex mutex_; // guards names_
    std::vector<std::string> names_;
};

} // namespace kdop
