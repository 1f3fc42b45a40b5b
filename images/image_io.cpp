#include "images/image_io.h"

#include "core/input_files.h"
#include "core/memory_budget.h"
#include "core/read_file.h"
#include "core/write_files.h"
#include "images/jpeg_guard.h"
#include "images/row_reader.h"
#include "images/srgb.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <sys/statvfs.h>

namespace kdop {

namespace {

// An error from OpenImageIO (or the codec library under it) as one line of text: it may span lines
// ("PNG read error: ...\nPNG library error") and, from a damaged file, hold control bytes, which
// are shown as \xNN rather than sent to the terminal.
std::string library_message(std::string_view text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.remove_suffix(1);
    std::string out;
    for (char ch : text) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (c == '\n')
            out += "; ";
        else if (c < 0x20 || c == 0x7f)
            out += fmt::format("\\x{:02x}", c);
        else
            out += ch;
    }
    return out;
}

// The exponent that turns a stored integer value into a linear one, or nullopt for sRGB.
std::optional<float> stored_gamma(const OIIO::ImageSpec& spec, InputSpace space) {
    if (space == InputSpace::linear) return 1.0f;
    if (space == InputSpace::srgb) return std::nullopt;
    if (spec.format.is_floating_point()) return 1.0f;
    std::string tag = spec.get_string_attribute("oiio:ColorSpace");
    std::ranges::transform(tag, tag.begin(), [](unsigned char c) { return std::tolower(c); });
    if (tag == "linear" || tag == "lin_srgb" || tag == "scene_linear" || tag == "raw") return 1.0f;
    if (tag.starts_with("gammacorrected")) {
        const float gamma = spec.get_float_attribute("oiio:Gamma", std::strtof(tag.c_str() + 14, nullptr));
        if (std::isfinite(gamma) && gamma > 0) return gamma;
    }
    return std::nullopt;
}

// Why the first three channels of `spec` are not color, or nullopt: they must be named R, G and B
// (in any case, or <layer>.R, <layer>.G, <layer>.B of one layer), as OpenImageIO names them for
// every format without names of its own and as EXR's reader puts them first. An EXR of Y, RY, BY
// (luminance and chroma) or of other layers alone would otherwise be read as if it were RGB.
std::optional<std::string> not_rgb(const OIIO::ImageSpec& spec) {
    auto lower = [](std::string s) {
        std::ranges::transform(s, s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        return s;
    };
    std::string layer;
    bool rgb = true;
    for (int c = 0; c < 3 && rgb; ++c) {
        const std::string name = lower(std::string(spec.channel_name(c)));
        const std::string wanted(1, "rgb"[c]);
        const std::size_t dot = name.rfind('.');
        const std::string prefix = dot == std::string::npos ? "" : name.substr(0, dot + 1);
        rgb = name.substr(prefix.size()) == wanted && (c == 0 || prefix == layer);
        layer = prefix;
    }
    if (rgb) return std::nullopt;
    std::string names;
    for (int c = 0; c < spec.nchannels && c < 8; ++c) names += (c ? ", " : "") + library_message(spec.channel_name(c));
    if (spec.nchannels > 8) names += ", ...";
    return fmt::format("its channels are {}; kdop reads color from channels named R, G and B (alpha and other "
                       "layers may follow), and does not guess what others hold",
                       names);
}

// `in`'s pixels, 8- or 16-bit (`Stored`), into `image`: read as stored, and every value a channel
// can hold converted once, by OpenImageIO's own conversion to float and then, for color, `decode`.
// The pixels are those of a float read, and a 1920x1080 sRGB PNG costs 256 powf, not six million.
template <class Stored>
Result<Image> read_through_table(OIIO::ImageInput& in, int channels, const auto& decode, const std::string& path,
                                 Image image) {
    constexpr std::size_t levels = std::size_t(std::numeric_limits<Stored>::max()) + 1;
    const OIIO::TypeDesc type = OIIO::BaseTypeFromC<Stored>::value;
    std::vector<Stored> every(levels);
    std::iota(every.begin(), every.end(), Stored(0));
    std::vector<float> as_value(levels), as_color(levels);
    if (!OIIO::convert_pixel_values(type, every.data(), OIIO::TypeDesc::FLOAT, as_value.data(), int(levels)))
        return fail(fmt::format("{}: cannot convert {} values to float", path, type.c_str()));
    std::ranges::transform(as_value, as_color.begin(), decode);
    std::vector<Stored> data(image.pixels.size() * std::size_t(channels));
    if (!in.read_image(0, 0, 0, channels, type, data.data()))
        return fail(fmt::format("{}: cannot read pixels: {}", path, library_message(in.geterror())));
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < channels; ++c) {
            const Stored v = data[i * std::size_t(channels) + std::size_t(c)];
            image.pixels[i][c] = c < 3 ? as_color[v] : as_value[v];
        }
    return image;
}

// Opens `file` (the /proc/self/fd path of an open descriptor where `name` is given) with the
// reader that `name`'s extension (else `file`'s) picks.
std::unique_ptr<OIIO::ImageInput> open_input(const std::string& file, const std::string& name,
                                             const OIIO::ImageSpec* config) {
    if (name.empty()) return OIIO::ImageInput::open(file, config);
    auto in = OIIO::ImageInput::create(name);
    OIIO::ImageSpec spec;
    if (!in || !in->open(file, spec, config ? *config : OIIO::ImageSpec())) return nullptr;
    return in;
}

// Every pixel of `in`: 8- and 16-bit files through a table of their values, others straight into
// the image's pixels.
Result<Image> read_whole(OIIO::ImageInput& in, int channels, std::optional<float> gamma, const auto& decode,
                         const std::string& path) {
    const OIIO::ImageSpec& spec = in.spec();
    Image image(spec.width, spec.height); // channels the file lacks stay 0, alpha 1
    if (spec.channelformats.empty() && spec.format == OIIO::TypeDesc::UINT8)
        return read_through_table<std::uint8_t>(in, channels, decode, path, std::move(image));
    if (spec.channelformats.empty() && spec.format == OIIO::TypeDesc::UINT16)
        return read_through_table<std::uint16_t>(in, channels, decode, path, std::move(image));
    // Other formats straight into the image's pixels, a channel a float apart and a pixel a vec4.
    if (!in.read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, image.pixels.data(), sizeof(glm::vec4)))
        return fail(fmt::format("{}: cannot read pixels: {}", path, library_message(in.geterror())));
    if (gamma != 1.0f) // sRGB (no gamma) or a power
        for (glm::vec4& p : image.pixels)
            for (int c = 0; c < std::min(channels, 3); ++c) p[c] = decode(p[c]);
    return image;
}

// The rows of an image read at a time for its corner: about 16 MiB of floats, at least one row.
std::uint32_t strip_rows(const OIIO::ImageSpec& spec, int channels, std::uint32_t height) {
    const std::uint64_t row = std::uint64_t(spec.width) * std::uint64_t(channels) * sizeof(float);
    return std::uint32_t(std::clamp<std::uint64_t>((16ull << 20) / row, 1, height));
}

// The top-left width x height pixels of `in`, read a strip of whole rows at a time (as floats:
// OpenImageIO's own conversion, then `decode`, so the pixels are a whole read's, bit for bit) and
// cropped: the rows below are never decoded, and the columns beyond never kept.
Result<Image> read_corner(OIIO::ImageInput& in, int channels, const auto& decode, const std::string& path,
                          std::uint32_t width, std::uint32_t height) {
    const OIIO::ImageSpec& spec = in.spec();
    const std::size_t row = std::size_t(spec.width) * std::size_t(channels);
    const std::uint32_t rows = strip_rows(spec, channels, height);
    std::vector<float> strip(row * rows);
    Image image(width, height); // channels the file lacks stay 0, alpha 1
    for (std::uint32_t y0 = 0; y0 < height; y0 += rows) {
        const std::uint32_t y1 = std::min(height, y0 + rows);
        if (!in.read_scanlines(0, 0, spec.y + int(y0), spec.y + int(y1), 0, 0, channels, OIIO::TypeDesc::FLOAT,
                               strip.data()))
            return fail(fmt::format("{}: cannot read pixels: {}", path, library_message(in.geterror())));
        for (std::uint32_t y = y0; y < y1; ++y)
            for (std::uint32_t x = 0; x < width; ++x)
                for (int c = 0; c < channels; ++c) {
                    const float v = strip[(y - y0) * row + std::size_t(x) * std::size_t(channels) + std::size_t(c)];
                    image.at(x, y)[c] = c < 3 ? decode(v) : v;
                }
    }
    return image;
}

// `needed`: the channels the caller needs, for the error when there are fewer: RGB (3) or a count
// of data channels. `corner`, where not 0x0, limits the read to the image's top-left corner of at
// most that size.
Result<Image> read_checked(const std::string& file, std::uint32_t max_side, InputSpace space, int needed,
                           const std::string& name, glm::uvec2 corner = {}) {
    const std::string& path = name.empty() ? file : name; // what messages name
    // Before OpenImageIO opens it: a device (/dev/zero) or a pipe would be read without end.
    if (auto why = not_a_readable_file(file)) return fail(fmt::format("{}: cannot read image: {}", path, *why));
    if (auto why = unsafe_jpeg_metadata(file)) return fail(fmt::format("{}: cannot read image: {}", path, *why));
    // Noted as the file it is, by its own name: an output that would replace it is refused naming
    // that, not the /proc/self/fd path it was read through.
    note_input(file, path);
    // Color as stored: readers of formats with unassociated alpha (PNG, TGA, TIFF) would otherwise
    // multiply it by alpha.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = open_input(file, name, &config);
    if (!in) {
        const std::string reason = library_message(OIIO::geterror());
        return fail(fmt::format("{}: cannot read image: {}", path, reason.empty() ? "unknown format" : reason));
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.nchannels < needed)
        return fail(needed == 3
                        ? fmt::format("{}: has {} channel(s); kdop needs RGB in the first three", path, spec.nchannels)
                        : fmt::format("{}: has {} channel(s); kdop needs {} here", path, spec.nchannels, needed));
    if (needed == 3)
        if (auto why = not_rgb(spec)) return fail(fmt::format("{}: {}", path, *why));
    if (spec.width <= 0 || spec.height <= 0 || spec.depth > 1)
        return fail(fmt::format("{}: not a 2-D image ({}x{}x{})", path, spec.width, spec.height, spec.depth));

    if (max_side && (std::uint64_t(spec.width) > max_side || std::uint64_t(spec.height) > max_side))
        return fail(fmt::format("{}: {}x{} is larger than the device allows: at most {} pixels on a side", path,
                                spec.width, spec.height, max_side));
    const int channels = std::min(spec.nchannels, 4);
    const std::optional<float> gamma = stored_gamma(spec, space);
    auto decode = [&](float v) {
        if (!gamma) return srgb_to_linear(v);
        return *gamma == 1.0f ? v : std::pow(v, *gamma);
    };
    const std::uint32_t width = corner.x ? std::min(corner.x, std::uint32_t(spec.width)) : spec.width;
    const std::uint32_t height = corner.y ? std::min(corner.y, std::uint32_t(spec.height)) : spec.height;
    const bool cropped = width < std::uint32_t(spec.width) || height < std::uint32_t(spec.height);
    if (cropped && decodes_by_rows(*in, file)) {
        // The corner, and a strip of whole rows.
        const std::uint64_t bytes = image_bytes(width, height) + std::uint64_t(spec.width) *
                                                                     strip_rows(spec, channels, height) *
                                                                     std::uint64_t(channels) * sizeof(float);
        if (auto ok = check_memory(
                fmt::format("{}: {}x{} pixels of a {}x{} image", path, width, height, spec.width, spec.height), bytes);
            !ok)
            return std::unexpected(ok.error());
        return read_corner(*in, channels, decode, path, width, height);
    }
    // The image, and the decoded pixels of an 8- or 16-bit file (as much as a reader that holds the
    // whole file's pixels takes besides: an interlaced PNG's), and a corner cut from it.
    const std::uint64_t bytes = image_bytes(spec.width, spec.height) +
                                std::uint64_t(spec.width) * spec.height * channels * 4 +
                                (cropped ? image_bytes(width, height) : 0);
    if (auto ok = check_memory(fmt::format("{}: a {}x{} image", path, spec.width, spec.height), bytes); !ok)
        return fail(cropped ? fmt::format("{}; only its top-left {}x{} pixels are used, which a PNG without "
                                          "interlacing or a scanline EXR gives without decoding the rest",
                                          ok.error().message, width, height)
                            : ok.error().message);
    auto image = read_whole(*in, channels, gamma, decode, path);
    if (!image || !cropped) return image;
    Image kept(width, height);
    for (std::uint32_t y = 0; y < height; ++y) std::copy_n(&image->at(0, y), width, &kept.at(0, y));
    return kept;
}

} // namespace

std::optional<InputSpace> parse_input_space(std::string_view text) {
    if (text == "file") return InputSpace::from_file;
    if (text == "linear") return InputSpace::linear;
    if (text == "srgb") return InputSpace::srgb;
    return std::nullopt;
}

namespace {

// What `read` gives, or the error of a reader that threw instead of reporting. Some of
// OpenImageIO's readers throw on a damaged file (its BMP reader lets std::length_error out of
// open() for an RLE image claiming billions of rows; found by tests/fuzz/image_fuzzer.cpp), so that
// is a read error of this file too. Memory that runs out in a reader despite the check on its
// header (taken by another process since) is said as that, with what is left, never as
// "std::bad_alloc".
template <class T>
Result<T> guarded(const std::string& path, const auto& read) {
    try {
        return read();
    } catch (const std::bad_alloc&) {
        return fail(fmt::format("{}: cannot read image: memory ran out while decoding it ({:.1f} GiB are available)",
                                path, double(available_memory()) / (1ull << 30)));
    } catch (const std::exception& e) {
        return fail(fmt::format("{}: cannot read image: {}", path, library_message(e.what())));
    }
}

} // namespace

Result<Image> read_image(const std::string& path, std::uint32_t max_side, InputSpace space, const std::string& name) {
    return guarded<Image>(name.empty() ? path : name, [&] { return read_checked(path, max_side, space, 3, name); });
}

Result<Image> read_image_corner(const std::string& path, std::uint32_t width, std::uint32_t height, InputSpace space) {
    return guarded<Image>(path, [&] { return read_checked(path, 0, space, 3, {}, {width, height}); });
}

Result<glm::uvec2> read_image_size(const std::string& path, const std::string& name) {
    const std::string& shown = name.empty() ? path : name;
    if (auto why = not_a_readable_file(path)) return fail(fmt::format("{}: cannot read image: {}", shown, *why));
    if (auto why = unsafe_jpeg_metadata(path)) return fail(fmt::format("{}: cannot read image: {}", shown, *why));
    return guarded<glm::uvec2>(shown, [&]() -> Result<glm::uvec2> {
        auto in = open_input(path, name, nullptr);
        if (!in) {
            const std::string reason = library_message(OIIO::geterror());
            return fail(fmt::format("{}: cannot read image: {}", shown, reason.empty() ? "unknown format" : reason));
        }
        const OIIO::ImageSpec& spec = in->spec();
        if (spec.width <= 0 || spec.height <= 0 || spec.depth > 1)
            return fail(fmt::format("{}: not a 2-D image ({}x{}x{})", shown, spec.width, spec.height, spec.depth));
        return glm::uvec2(spec.width, spec.height);
    });
}

Result<Image> read_data_image(const std::string& path, int channels, const std::string& name) {
    return guarded<Image>(name.empty() ? path : name,
                          [&] { return read_checked(path, 0, InputSpace::linear, channels, name); });
}

Result<Image> read_finite_image(const std::string& path, std::string_view why, InputSpace space) {
    auto image = read_image(path, 0, space);
    if (!image) return image;
    for (std::uint32_t y = 0; y < image->height; ++y)
        for (std::uint32_t x = 0; x < image->width; ++x) {
            const glm::vec4& p = image->at(x, y);
            if (!std::isfinite(p.r) || !std::isfinite(p.g) || !std::isfinite(p.b))
                return fail(
                    fmt::format("{}: pixel ({}, {}) is not finite ({}, {}, {}); {}", path, x, y, p.r, p.g, p.b, why));
        }
    return image;
}

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
    if (type == OIIO::TypeDesc::HALF) return {v, std::max(std::abs(v) * 1e-3f, 1e-7f)};
    return {v, 0.0f};
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
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const glm::vec4& p = image.pixels[i];
        // RGBE keeps about 8 bits of the largest channel's magnitude for all three, and no pixel
        // dimmer than about 1e-32.
        const float rgbe = std::max({std::abs(p.r), std::abs(p.g), std::abs(p.b)}) / 64.0f + 1e-32f;
        for (int c = 0; c < channels; ++c) {
            const float read = data[i * channels + c];
            const bool encoded = c < 3 && !spec.format.is_floating_point();
            const Expected e = stored(encoded ? linear_to_srgb(p[c]) : p[c], spec.format);
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

// The 8-bit values of `image`'s first `channels` channels as an 8-bit file stores them: color
// sRGB-encoded, alpha as it is, each converted by OpenImageIO's own conversion (what it would do to
// the floats), a block of rows at a time, so no float copy of the whole image is made.
std::vector<std::uint8_t> encoded_bytes(const Image& image, int channels) {
    const std::size_t per_row = std::size_t(image.width) * std::size_t(channels);
    std::vector<std::uint8_t> bytes(per_row * image.height);
    std::vector<float> rows;
    constexpr std::uint32_t kRows = 16;
    for (std::uint32_t y0 = 0; y0 < image.height; y0 += kRows) {
        const std::uint32_t y1 = std::min(image.height, y0 + kRows);
        rows.clear();
        for (std::size_t i = std::size_t(y0) * image.width; i < std::size_t(y1) * image.width; ++i) {
            const glm::vec4& p = image.pixels[i];
            for (int c = 0; c < channels; ++c) rows.push_back(c < 3 ? linear_to_srgb(p[c]) : p[c]);
        }
        OIIO::convert_pixel_values(OIIO::TypeDesc::FLOAT, rows.data(), OIIO::TypeDesc::UINT8,
                                   bytes.data() + std::size_t(y0) * per_row, int(rows.size()));
    }
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

// Writes `image` to `file` (a temporary) and checks it; errors name `path`, the file's final name.
// With `data_channels`, the image is data: that many of its channels, so named, in a float format.
Result<void> write_checked(const std::filesystem::path& file, const std::string& path, const Image& image,
                           std::span<const char* const> data_channels = {}) {
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

    // RGBA where the format has alpha, else RGB (Radiance HDR stores three channels only). An opaque
    // PNG leaves its alpha out: a quarter fewer bytes to compress, the same pixels read back.
    const bool png = format == "png";
    const int channels = data ? int(data_channels.size()) : out->supports("alpha") && !(png && opaque(image)) ? 4 : 3;
    OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), channels,
                         OIIO::TypeDesc::FLOAT);
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

Result<void> write_image_to(const std::filesystem::path& temporary, const std::string& path, const Image& image) {
    return named_as_output(write_checked(temporary, path, image), temporary, path);
}

Result<void> write_data_image_to(const std::filesystem::path& temporary, const std::string& path, const Image& image,
                                 std::span<const char* const> channels) {
    return named_as_output(write_checked(temporary, path, image, channels), temporary, path);
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
