#include "harness/staged_images.h"

#include "images/image_io.h"

#include <fmt/format.h>

namespace kdop {

Result<void> StagedImages::add(const std::string& name, const Image& image) {
    if (scratch_->path.empty()) return fail("cannot create a scratch folder for the frames (is TMPDIR writable?)");
    const std::filesystem::path staged = scratch_->path / name;
    std::error_code ec;
    std::filesystem::create_directories(staged.parent_path(), ec);
    // Another thread may have made it meanwhile.
    if (ec && !std::filesystem::is_directory(staged.parent_path()))
        return fail(fmt::format("{}: {}", staged.parent_path().string(), ec.message()));
    if (auto ok = write_image(staged.string(), image); !ok) return ok;
    std::lock_guard lock(mutex_);
    names_.push_back(name);
    return {};
}

std::vector<OutputWriter> StagedImages::writers(const std::filesystem::path& dir) const {
    std::vector<OutputWriter> out;
    for (const std::string& name : names_) {
        const std::filesystem::path staged = scratch_->path / name;
        // A copy, not a rename: the scratch folder may be on another file system.
        out.push_back({dir / name, [staged, path = dir / name](const std::filesystem::path& to) -> Result<void> {
                           std::error_code ec;
                           std::filesystem::copy_file(staged, to, ec);
                           if (ec) return fail(fmt::format("{}: {}", path.string(), ec.message()));
                           return {};
                       }});
    }
    return out;
}

} // namespace kdop
