#include "harness/staged_images.h"

#include "core/read_file.h"
#include "images/image_io.h"

#include <fmt/format.h>

#include <fstream>

namespace kdop {

namespace {

// Where `name` is staged in `scratch`, its folder made.
Result<std::filesystem::path> staging_path(const ScratchDirectory& scratch, const std::string& name) {
    if (scratch.path.empty()) return fail("cannot create a scratch folder for the frames (is TMPDIR writable?)");
    const std::filesystem::path staged = scratch.path / name;
    std::error_code ec;
    std::filesystem::create_directories(staged.parent_path(), ec);
    // Another thread may have made it meanwhile.
    if (ec && !std::filesystem::is_directory(staged.parent_path()))
        return fail(fmt::format("{}: {}", staged.parent_path().string(), ec.message()));
    return staged;
}

} // namespace

Result<void> write_raw(const std::filesystem::path& path, std::span<const float> values) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size_bytes()));
    if (!out.flush()) return fail(fmt::format("{}: cannot write a staged frame", path.string()));
    return {};
}

Result<void> write_raw(const std::filesystem::path& path, const Image& image) {
    return write_raw(path, std::span(reinterpret_cast<const float*>(image.pixels.data()), image.pixels.size() * 4));
}

Result<void> read_raw(const std::filesystem::path& path, std::span<float> values) {
    std::ifstream in(path, std::ios::binary);
    in.read(reinterpret_cast<char*>(values.data()), std::streamsize(values.size_bytes()));
    if (!in) return fail(fmt::format("{}: cannot read a staged frame back", path.string()));
    return {};
}

Result<Image> read_raw_image(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height) {
    Image image(width, height);
    if (auto ok = read_raw(path, std::span(reinterpret_cast<float*>(image.pixels.data()), image.pixels.size() * 4));
        !ok)
        return std::unexpected(ok.error());
    return image;
}

Result<void> StagedImages::add(const std::string& name, const Image& image) {
    auto staged = staging_path(*scratch_, name);
    if (!staged) return std::unexpected(staged.error());
    if (auto ok = write_image(staged->string(), image); !ok) return ok;
    std::lock_guard lock(mutex_);
    names_.push_back(name);
    return {};
}

Result<void> StagedImages::add_encoded(const std::string& name, const std::string& bytes) {
    auto staged = staging_path(*scratch_, name);
    if (!staged) return std::unexpected(staged.error());
    std::ofstream out(*staged, std::ios::binary);
    out << bytes;
    out.close();
    if (!out) return fail(fmt::format("{}: cannot write", staged->string()));
    std::lock_guard lock(mutex_);
    names_.push_back(name);
    return {};
}

Result<std::string> StagedImages::bytes(const std::string& name) const { return read_own_file(scratch_->path / name); }

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
