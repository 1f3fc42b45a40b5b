#include "image_io.h"

#include "memory_budget.h"
#include "write_files.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace kdop {

Result<Image> read_image(const std::string& path, std::uint32_t max_side) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        std::string reason = OIIO::geterror();
        return fail(fmt::format("{}: cannot read image: {}", path, reason.empty() ? "unknown format" : reason));
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.nchannels < 3)
        return fail(fmt::format("{}: has {} channel(s); kdop needs RGB in the first three", path, spec.nchannels));
    if (spec.width <= 0 || spec.height <= 0 || spec.depth > 1)
        return fail(fmt::format("{}: not a 2-D image ({}x{}x{})", path, spec.width, spec.height, spec.depth));

    if (max_side && (std::uint64_t(spec.width) > max_side || std::uint64_t(spec.height) > max_side))
        return fail(fmt::format("{}: {}x{} is larger than the device allows: at most {} pixels on a side", path,
                                spec.width, spec.height, max_side));
    const int channels = std::min(spec.nchannels, 4);
    // The decoded pixels and the image made of them, both float.
    const std::uint64_t bytes =
        image_bytes(spec.width, spec.height) + std::uint64_t(spec.width) * spec.height * channels * 4;
    if (auto ok = check_memory(fmt::format("{}: a {}x{} image", path, spec.width, spec.height), bytes); !ok)
        return std::unexpected(ok.error());
    std::vector<float> data(std::size_t(spec.width) * spec.height * channels);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, data.data()))
        return fail(fmt::format("{}: cannot read pixels: {}", path, in->geterror()));

    Image image(spec.width, spec.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < channels; ++c) image.pixels[i][c] = data[i * channels + c];
    return image;
}

Result<void> write_image(const std::string& path, const Image& image) {
    namespace fs = std::filesystem;
    fs::path final_path(path);
    // The temporary keeps the extension, which tells OpenImageIO the format.
    const fs::path temporary = temporary_path_for(final_path);
    auto out = OIIO::ImageOutput::create(temporary.string());
    if (!out) return fail(fmt::format("{}: no image format for this extension: {}", path, OIIO::geterror()));

    OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), 4, OIIO::TypeDesc::FLOAT);
    // OpenImageIO stamps EXR files with the time of writing unless told a time. The time is not an
    // input, so, as reproducible builds do, record the epoch: same pixels, same bytes.
    spec.attribute("DateTime", "1970:01:01 00:00:00");
    if (!out->open(temporary.string(), spec)) return fail(fmt::format("{}: cannot write: {}", path, out->geterror()));
    bool ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
    ok = out->close() && ok;
    std::error_code ec;
    if (!ok) {
        fs::remove(temporary, ec);
        return fail(fmt::format("{}: cannot write: {}", path, out->geterror()));
    }
    fs::rename(temporary, final_path, ec);
    if (ec) {
        const std::string reason = ec.message(); // before remove() reuses ec
        fs::remove(temporary, ec);
        return fail(fmt::format("{}: cannot move into place: {}", path, reason));
    }
    return {};
}

Result<void> write_images(const std::vector<ImageFile>& files) {
    namespace fs = std::filesystem;
    std::vector<fs::path> temporaries;
    auto abandon = [&](Error error) -> Result<void> {
        std::error_code ignored;
        for (const fs::path& p : temporaries) fs::remove(p, ignored);
        return std::unexpected(std::move(error));
    };
    for (const ImageFile& f : files) {
        std::error_code ec;
        if (f.path.has_parent_path()) fs::create_directories(f.path.parent_path(), ec);
        if (ec)
            return abandon(
                {fmt::format("{}: cannot create directory: {}", f.path.parent_path().string(), ec.message())});
        temporaries.push_back(temporary_path_for(f.path));
        if (auto ok = write_image(temporaries.back().string(), *f.image); !ok) return abandon(ok.error());
    }
    for (std::size_t i = 0; i < files.size(); ++i) {
        std::error_code ec;
        fs::rename(temporaries[i], files[i].path, ec);
        if (ec) return abandon({fmt::format("{}: cannot move into place: {}", files[i].path.string(), ec.message())});
    }
    return {};
}

} // namespace kdop
