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
#include <span>
#include <string>
#include <vector>

namespace kdop {

// A frame or FLIP map staged for this process alone: its floats as they are in memory. The process
// reads back only what it wrote itself, moments before, so no format is needed, and many frames are
// staged and dropped during a pass (report.html's viewer, the picture's frame): an EXR's
// compression and OpenImageIO's checks cost more there than the whole copy (written by hand for
// that reason). The reader gives the size, the frame's.
Result<void> write_raw(const std::filesystem::path& path, std::span<const float> values);
Result<void> write_raw(const std::filesystem::path& path, const Image& image);
Result<void> read_raw(const std::filesystem::path& path, std::span<float> values);
Result<Image> read_raw_image(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height);

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
