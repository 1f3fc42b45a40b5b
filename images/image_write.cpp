// Writing images: the codecs (images/image_codecs.h) encode each to a temporary in their module,
// and the files are renamed into place here, all or nothing (core/write_files.h).
#include "images/image_io.h"

#include "core/write_files.h"
#include "images/image_codecs.h"

namespace kdop {

Result<void> write_image_to(const std::filesystem::path& temporary, const std::string& path, const Image& image,
                            FloatPrecision precision) {
    return write_data_image_to(temporary, path, image, {}, precision);
}

Result<void> write_data_image_to(const std::filesystem::path& temporary, const std::string& path, const Image& image,
                                 std::span<const char* const> channels, FloatPrecision precision) {
    auto codecs = image_codecs();
    if (!codecs) return std::unexpected(codecs.error());
    return (*codecs)->write(temporary, path, image, channels, precision);
}

Result<void> check_image_writable(const std::string& path) {
    auto codecs = image_codecs();
    if (!codecs) return std::unexpected(codecs.error());
    return (*codecs)->check_writable(path);
}

Result<void> write_image(const std::string& path, const Image& image) {
    return write_atomically(
        {{path, [&](const std::filesystem::path& file) { return write_image_to(file, path, image); }}});
}

OutputWriter image_writer(std::filesystem::path path, std::shared_ptr<const Image> image) {
    const std::string name = path.string();
    return {std::move(path),
            [image, name](const std::filesystem::path& file) { return write_image_to(file, name, *image); }};
}

Result<void> write_images(const std::vector<ImageFile>& files) {
    std::vector<OutputWriter> writers;
    for (const ImageFile& f : files)
        writers.push_back({f.path, [&f](const std::filesystem::path& file) {
                               return write_image_to(file, f.path.string(), *f.image);
                           }});
    return write_atomically(writers);
}

} // namespace kdop
