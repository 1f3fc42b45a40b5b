// OpenImageIO's side of writing (images/image_codecs.h): an image encoded to a temporary file and
// read back to check it. Its renaming into place, all or nothing, is the executable's
// (images/image_write.cpp).
#include "images/oiio_codecs.h"

#include "images/library_message.h"
#include "images/srgb.h"
#include "images/srgb_bytes.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <sys/statvfs.h>

namespace kdop::oiio {

namespace {

// Formats that would not give back the values written: kdop writes data, not pictures. JPEG also
// ends the process on a write error (libjpeg's error handler exits) instead of reporting it.
bool is_lossy(std::string_view format) {
    return format == "jpeg" || format == "webp" || format == "heif" || format == "gif";
}

// What a channel value becomes when stored as `type` (as OpenImageIO converts it; `v` already
// encoded for an integer type), and how far the read-back value may be from it.
struct Expected {
    float value, tolerance;
};
Expected stored(float v, OIIO::TypeDesc type) {
    if (!type.is_floating_point()) {
        const float levels = type == OIIO::TypeDesc::UINT8 ? 255.0f : 65535.0f;
        const float clamped = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
        return {std::round(clamped * levels) / levels, 1.01f / levels};
    }
    // Half: verify_written compares with the nearest halves (nearest_halves).
    return {v, 0.0f};
}

// Each channel value of `image` rounded to the nearest half float, as OpenImageIO rounds it when
// it writes halves (Imath's conversion): what a half EXR must read back as, exactly.
std::vector<float> nearest_halves(const Image& image) {
    const int n = int(image.pixels.size() * 4);
    std::vector<std::uint16_t> halves(std::size_t(n), 0);
    std::vector<float> out(std::size_t(n), 0.0f);
    OIIO::convert_pixel_values(OIIO::TypeDesc::FLOAT, image.pixels.data(), OIIO::TypeDesc::HALF, halves.data(), n);
    OIIO::convert_pixel_values(OIIO::TypeDesc::HALF, halves.data(), OIIO::TypeDesc::FLOAT, out.data(), n);
    return out;
}

// The file just written, opened to be read back, if it is of the size written.
Result<std::unique_ptr<OIIO::ImageInput>> open_written(const std::string& file, std::uint32_t width,
                                                       std::uint32_t height, const std::string& path) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1); // as written: color not multiplied by alpha
    auto in = OIIO::ImageInput::open(file, &config);
    if (!in)
        return fail(fmt::format("{}: written, but cannot be read back: {}", path, library_message(OIIO::geterror())));
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width != int(width) || spec.height != int(height))
        return fail(fmt::format("{}: written as {}x{}, not {}x{}", path, spec.width, spec.height, width, height));
    return in;
}

// Reads the file just written back and compares it with `image`, so a writer that reports success
// on a full disk (OpenImageIO's PNG, BMP and TGA writers do) cannot leave a short or wrong file.
Result<void> verify_written(const std::string& file, const Image& image, const std::string& path) {
    auto opened = open_written(file, image.width, image.height, path);
    if (!opened) return std::unexpected(opened.error());
    OIIO::ImageInput* in = opened->get();
    const OIIO::ImageSpec& spec = in->spec();
    const int channels = std::min(spec.nchannels, 4);
    std::vector<float> data(std::size_t(spec.width) * spec.height * channels);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, data.data()))
        return fail(fmt::format("{}: written, but does not read back whole (disk full?): {}", path,
                                library_message(in->geterror())));
    const bool shared_exponent = std::string_view(in->format_name()) == "hdr";
    const std::vector<float> halves =
        spec.format == OIIO::TypeDesc::HALF ? nearest_halves(image) : std::vector<float>{};
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const glm::vec4& p = image.pixels[i];
        // RGBE keeps about 8 bits of the largest channel's magnitude for all three, and no pixel
        // dimmer than about 1e-32.
        const float rgbe = std::max({std::abs(p.r), std::abs(p.g), std::abs(p.b)}) / 64.0f + 1e-32f;
        for (int c = 0; c < channels; ++c) {
            const float read = data[i * channels + c];
            const bool encoded = c < 3 && !spec.format.is_floating_point();
            const Expected e = halves.empty() ? stored(encoded ? linear_to_srgb(p[c]) : p[c], spec.format)
                                              : Expected{halves[i * 4 + c], 0.0f};
            const float tolerance = shared_exponent && c < 3 ? rgbe : e.tolerance;
            const bool same =
                std::isnan(e.value) ? std::isnan(read) : std::abs(read - e.value) <= tolerance || read == e.value;
            if (!same)
                return fail(fmt::format("{}: written, but pixel ({}, {}) reads back as {} instead of {}", path,
                                        i % image.width, i / image.width, read, e.value));
        }
    }
    return {};
}

// The 8-bit values of `image`'s first `channels` channels (each in [0, 1]) as an 8-bit file stores
// them: color sRGB-encoded, alpha as it is, each as OpenImageIO's conversion of the floats would
// give it (images/srgb_bytes.h).
std::vector<std::uint8_t> encoded_bytes(const Image& image, int channels) {
    const ByteSteps& srgb = ByteSteps::srgb();
    const ByteSteps& unit = ByteSteps::unit();
    std::vector<std::uint8_t> bytes(image.pixels.size() * std::size_t(channels));
    std::uint8_t* out = bytes.data();
    for (const glm::vec4& p : image.pixels)
        for (int c = 0; c < channels; ++c) *out++ = c < 3 ? srgb.code(p[c]) : unit.code(p[c]);
    return bytes;
}

// verify_written for an 8-bit file: it must read back as exactly the bytes written.
Result<void> verify_written_bytes(const std::string& file, const std::vector<std::uint8_t>& bytes, std::uint32_t width,
                                  std::uint32_t height, const std::string& path) {
    auto opened = open_written(file, width, height, path);
    if (!opened) return std::unexpected(opened.error());
    OIIO::ImageInput* in = opened->get();
    const OIIO::ImageSpec& spec = in->spec();
    const int channels = int(bytes.size() / (std::size_t(width) * height));
    if (spec.nchannels < channels)
        return fail(fmt::format("{}: written with {} channels, not {}", path, spec.nchannels, channels));
    std::vector<std::uint8_t> read(bytes.size());
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, read.data()))
        return fail(fmt::format("{}: written, but does not read back whole (disk full?): {}", path,
                                library_message(in->geterror())));
    const auto differs = std::mismatch(read.begin(), read.end(), bytes.begin());
    if (differs.first != read.end()) {
        const std::size_t i = std::size_t(differs.first - read.begin()) / std::size_t(channels);
        return fail(fmt::format("{}: written, but pixel ({}, {}) reads back as {} instead of {}", path, i % width,
                                i / width, int(*differs.first), int(*differs.second)));
    }
    return {};
}

} // namespace

namespace {

// Whether Radiance HDR (RGBE: a shared exponent, no sign) can hold every RGB value of `image`.
bool fits_rgbe(const Image& image) {
    for (const glm::vec4& p : image.pixels)
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(p[c]) || p[c] < 0) return false;
    return true;
}

// Whether every pixel's alpha is 1.
bool opaque(const Image& image) {
    return std::all_of(image.pixels.begin(), image.pixels.end(), [](const glm::vec4& p) { return p.a == 1.0f; });
}

struct OutsideValue {
    std::uint32_t x, y;
    float value;
};
// The first channel value (of the first `channels`) that is not in [0, 1], NaN included.
std::optional<OutsideValue> first_outside_unit_range(const Image& image, int channels) {
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < channels; ++c)
            if (!(image.pixels[i][c] >= 0.0f && image.pixels[i][c] <= 1.0f))
                return OutsideValue{std::uint32_t(i % image.width), std::uint32_t(i / image.width), image.pixels[i][c]};
    return std::nullopt;
}

// "; the disk is full" where the folder of `file` has no room left: the codecs' own words for a
// write cut short ("Not a PNG file" on reading it back) do not say so.
std::string disk_full(const std::filesystem::path& file) {
    struct statvfs fs {};
    const std::filesystem::path folder = file.has_parent_path() ? file.parent_path() : ".";
    if (statvfs(folder.c_str(), &fs) != 0) return {};
    return std::uint64_t(fs.f_bavail) * fs.f_frsize < 64 * 1024 ? "; the disk is full (no space left on the device)"
                                                                : "";
}

// `bytes` written to `file`, every error of the writes and the close reported, naming `path`.
Result<void> write_bytes(const std::filesystem::path& file, const std::vector<unsigned char>& bytes,
                         const std::string& path) {
    std::FILE* f = std::fopen(file.c_str(), "wb");
    if (!f) return fail(fmt::format("{}: cannot write: {}{}", path, std::strerror(errno), disk_full(file)));
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    const int error = errno;
    const bool closed = std::fclose(f) == 0;
    if (!written || !closed)
        return fail(
            fmt::format("{}: cannot write: {}{}", path, std::strerror(written ? errno : error), disk_full(file)));
    return {};
}

// Half's largest finite value: a float beyond it would be written as infinity.
constexpr float kHalfMax = 65504.0f;

// The first finite value of the first `channels` channels beyond half's range.
std::optional<OutsideValue> first_beyond_half(const Image& image, int channels) {
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < channels; ++c)
            if (const float v = image.pixels[i][c]; std::isfinite(v) && std::abs(v) > kHalfMax)
                return OutsideValue{std::uint32_t(i % image.width), std::uint32_t(i / image.width), v};
    return std::nullopt;
}

// Writes `image` to `file` (a temporary) and checks it; errors name `path`, the file's final name.
// With `data_channels`, the image is data: that many of its channels, so named, in a float format.
Result<void> write_checked(const std::filesystem::path& file, const std::string& path, const Image& image,
                           std::span<const char* const> data_channels, FloatPrecision precision) {
    // The temporary keeps the extension, which tells OpenImageIO the format.
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out)
        return fail(fmt::format("{}: no image format for this extension: {}", path, library_message(OIIO::geterror())));
    const std::string_view format = out->format_name();
    if (is_lossy(format))
        return fail(fmt::format("{}: {} is lossy and would not keep the values; write EXR (or PNG for a picture)", path,
                                format));
    if (format == "hdr" && !fits_rgbe(image))
        return fail(fmt::format("{}: Radiance HDR cannot hold negative or non-finite values; write EXR", path));
    const bool data = !data_channels.empty();
    if (data && format != "openexr" && format != "tiff")
        return fail(fmt::format("{}: {} does not keep the floats data holds; write EXR", path, format));
    const bool half_floats = precision == FloatPrecision::half;
    if (half_floats && format != "openexr")
        return fail(fmt::format("{}: half floats are written to EXR only, not {}", path, format));

    // RGBA where the format has alpha, else RGB (Radiance HDR stores three channels only). An opaque
    // PNG leaves its alpha out: a quarter fewer bytes to compress, the same pixels read back.
    const bool png = format == "png";
    const int channels = data ? int(data_channels.size()) : out->supports("alpha") && !(png && opaque(image)) ? 4 : 3;
    if (half_floats)
        if (auto beyond = first_beyond_half(image, channels))
            return fail(fmt::format("{}: pixel ({}, {}) holds {}, beyond the largest half float ({}); write it as "
                                    "full floats",
                                    path, beyond->x, beyond->y, beyond->value, kHalfMax));
    OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), channels,
                         half_floats ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
    if (data) {
        spec.channelnames.assign(data_channels.begin(), data_channels.end());
        spec.alpha_channel = -1;
    }
    // OpenImageIO stamps EXR files with the time of writing unless told a time. The time is not an
    // input, so, as reproducible builds do, record the epoch: same pixels, same bytes.
    spec.attribute("DateTime", "1970:01:01 00:00:00");
    // Color and alpha are stored as they are: PNG and TGA writers would otherwise divide color by
    // alpha (and the readers multiply it back), which changes any pixel that is not opaque.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    // A PNG says what it holds (its sRGB chunk); other integer formats have no tag, and sRGB is what
    // readers take them to hold.
    if (png) {
        spec.attribute("oiio:ColorSpace", "sRGB");
        // Each row stored as its difference from the row above, deflated at zlib's level 4: on
        // kdop's frames and FLIP maps 2.5x to 3.4x faster to write than OpenImageIO's default
        // (level 6, each row's filter chosen by trying all five) and a few percent smaller
        // (docs/results.md, "Maps from the measurement"): report.html's viewer writes hundreds.
        spec.attribute("png:compressionLevel", 4);
        constexpr int kPngFilterUp = 0x20; // libpng's PNG_FILTER_UP (png.h, not otherwise needed here)
        spec.attribute("png:filter", kPngFilterUp);
    }
    // A PNG is encoded in memory and its bytes written here, where a full disk is an error: read
    // back, as other formats are checked below, it cost a fifth of report.html's viewer frames.
    std::vector<unsigned char> in_memory;
    OIIO::Filesystem::IOVecOutput memory(in_memory);
    if (png) {
        OIIO::Filesystem::IOProxy* proxy = &memory;
        spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    }
    if (!out->open(file.string(), spec))
        return fail(fmt::format("{}: cannot write: {}", path, library_message(out->geterror())));
    // A format that stores integers (PNG, BMP, TGA) keeps 0..1; clamping anything else away would
    // write a different image than asked, so it is refused (the temporary is removed by the caller).
    if (!out->spec().format.is_floating_point()) {
        if (auto outside = first_outside_unit_range(image, channels)) {
            // Closed whole (black), or libpng prints "No IDATs written into file" on stderr before
            // kdop's message; the temporary is removed all the same.
            const std::vector<float> black(std::size_t(image.width) * image.height * channels, 0.0f);
            out->write_image(OIIO::TypeDesc::FLOAT, black.data());
            out->close();
            return fail(fmt::format("{}: {} stores values from 0 to 1, and pixel ({}, {}) holds {}; write EXR or TIFF "
                                    "to keep it, or tone-map the image first",
                                    path, format, outside->x, outside->y, outside->value));
        }
    }
    // Integer formats hold sRGB-encoded color, as viewers expect; float formats the linear values.
    const bool encode = !out->spec().format.is_floating_point();
    bool ok = false;
    std::vector<std::uint8_t> bytes; // 8-bit formats (PNG): the bytes written, to check the file by
    if (out->spec().format == OIIO::TypeDesc::UINT8) {
        bytes = encoded_bytes(image, channels);
        ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
    } else if (encode) {
        std::vector<glm::vec4> encoded = image.pixels;
        for (glm::vec4& p : encoded) p = glm::vec4(linear_to_srgb(p.r), linear_to_srgb(p.g), linear_to_srgb(p.b), p.a);
        ok = out->write_image(OIIO::TypeDesc::FLOAT, encoded.data(), sizeof(glm::vec4));
    } else {
        ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data(), sizeof(glm::vec4));
    }
    ok = out->close() && ok;
    if (!ok)
        return fail(fmt::format("{}: cannot write: {}{}", path, library_message(out->geterror()), disk_full(file)));
    if (png) return write_bytes(file, in_memory, path);
    auto verified = bytes.empty() ? verify_written(file.string(), image, path)
                                  : verify_written_bytes(file.string(), bytes, image.width, image.height, path);
    if (!verified) return fail(verified.error().message + disk_full(file));
    return verified;
}

// What write_checked gave, its messages naming `path` instead of the temporary it was given.
Result<void> named_as_output(Result<void> written, const std::filesystem::path& temporary, const std::string& path) {
    if (written) return written;
    // The codecs' own words name the file they were given, the temporary; the user knows the output.
    std::string message = written.error().message;
    const std::string shown = temporary.string();
    for (std::size_t at = message.find(shown); at != std::string::npos; at = message.find(shown, at + path.size()))
        message.replace(at, shown.size(), path);
    return fail(message);
}

} // namespace

Result<void> write(const std::filesystem::path& temporary, const std::string& path, const Image& image,
                   std::span<const char* const> data_channels, FloatPrecision precision) {
    return named_as_output(write_checked(temporary, path, image, data_channels, precision), temporary, path);
}

Result<void> check_writable(const std::string& path) {
    if (OIIO::ImageOutput::create(path)) return {};
    return usage_fail(fmt::format("{}: no image format for this extension", path)); // the name is at fault
}

} // namespace kdop::oiio
