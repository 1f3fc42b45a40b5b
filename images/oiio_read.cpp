// OpenImageIO's side of reading (images/image_codecs.h): opening a file, checking its header and
// decoding its pixels to linear RGB. The checks before a file is opened are the executable's
// (images/image_read.cpp).
#include "images/oiio_codecs.h"

#include "core/memory_budget.h"
#include "images/header_checks.h"
#include "images/library_message.h"
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
#include <string_view>
#include <sys/statvfs.h>

namespace kdop::oiio {

namespace {

// The exponent that turns a stored integer value into a linear one, or nullopt for sRGB.
std::optional<float> stored_gamma(const OIIO::ImageSpec& spec, InputSpace space) {
    if (space == InputSpace::linear) return 1.0f;
    if (space == InputSpace::srgb) return std::nullopt;
    if (spec.format.is_floating_point()) return 1.0f;
    std::string tag = spec.get_string_attribute("oiio:ColorSpace");
    std::ranges::transform(tag, tag.begin(), [](unsigned char c) { return std::tolower(c); });
    if (tag == "linear" || tag == "lin_srgb" || tag == "scene_linear" || tag == "raw") return 1.0f;
    // OpenImageIO 2.4 tags its own files "GammaCorrected2.2" and a PNG whose gAMA chunk says so
    // (without sRGB's chunk) "Gamma2.2".
    for (std::string_view prefix : {"gammacorrected", "gamma"})
        if (tag.starts_with(prefix)) {
            const float gamma =
                spec.get_float_attribute("oiio:Gamma", std::strtof(tag.c_str() + prefix.size(), nullptr));
            if (std::isfinite(gamma) && gamma > 0) return gamma;
            break;
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
                           const std::string& name, glm::uvec2 corner) {
    const std::string& path = name.empty() ? file : name; // what messages name
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

    if (auto ok = check_max_side(path, spec.width, spec.height, max_side); !ok) return std::unexpected(ok.error());
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
    // The whole read, and a corner cut from it.
    const std::uint64_t bytes =
        whole_read_bytes(spec.width, spec.height, channels) + (cropped ? image_bytes(width, height) : 0);
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

// What `decode` gives, or the error of a reader that threw instead of reporting. Some of
// OpenImageIO's readers throw on a damaged file (its BMP reader lets std::length_error out of
// open() for an RLE image claiming billions of rows; found by tests/fuzz/image_fuzzer.cpp), so that
// is a read error of this file too. Memory that runs out in a reader despite the check on its
// header (taken by another process since) is said as that, with what is left, never as
// "std::bad_alloc".
template <class T>
Result<T> guarded(const std::string& path, const auto& decode) {
    try {
        return decode();
    } catch (const std::bad_alloc&) {
        return fail(fmt::format("{}: cannot read image: memory ran out while decoding it ({:.1f} GiB are available)",
                                path, double(available_memory()) / (1ull << 30)));
    } catch (const std::exception& e) {
        return fail(fmt::format("{}: cannot read image: {}", path, library_message(e.what())));
    }
}

} // namespace

Result<Image> read(const std::string& file, const ImageRead& r) {
    return guarded<Image>(r.name.empty() ? file : r.name,
                          [&] { return read_checked(file, r.max_side, r.space, r.needed, r.name, r.corner); });
}

Result<glm::uvec2> read_size(const std::string& file, const std::string& name) {
    const std::string& shown = name.empty() ? file : name;
    return guarded<glm::uvec2>(shown, [&]() -> Result<glm::uvec2> {
        auto in = open_input(file, name, nullptr);
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

} // namespace kdop::oiio
