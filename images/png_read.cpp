#include "images/png_read.h"

#include "images/header_checks.h"
#include "images/srgb.h"

#include <png.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string_view>

namespace kdop {
namespace {

struct PlainHeader {
    std::uint32_t width = 0, height = 0;
    int channels = 0;
};

std::uint32_t big_endian(const unsigned char* b) {
    return std::uint32_t(b[0]) << 24 | std::uint32_t(b[1]) << 16 | std::uint32_t(b[2]) << 8 | b[3];
}

// The header of `f` where it is a plain PNG, its chunks walked up to the first IDAT; nothing
// otherwise, or where the walk fails (the codecs then report it).
std::optional<PlainHeader> plain_header(std::FILE* f) {
    std::array<unsigned char, 8 + 8 + 13> start{}; // signature, IHDR's length and type, IHDR
    if (std::fread(start.data(), 1, start.size(), f) != start.size()) return std::nullopt;
    if (png_sig_cmp(start.data(), 0, 8) != 0 || std::memcmp(start.data() + 12, "IHDR", 4) != 0 ||
        big_endian(start.data() + 8) != 13)
        return std::nullopt;
    const unsigned char* ihdr = start.data() + 16;
    const int depth = ihdr[8], color_type = ihdr[9], interlace = ihdr[12];
    if (depth != 8 || (color_type != PNG_COLOR_TYPE_RGB && color_type != PNG_COLOR_TYPE_RGB_ALPHA)) return std::nullopt;
    // Interlaced: the codecs read such a file to its end (IEND and its CRC) and refuse one cut short
    // after its pixels, which libpng's simplified API does not look at. Neither kdop nor
    // OpenImageIO writes one.
    if (interlace != PNG_INTERLACE_NONE) return std::nullopt;
    const PlainHeader header{big_endian(ihdr), big_endian(ihdr + 4), color_type == PNG_COLOR_TYPE_RGB ? 3 : 4};
    if (header.width == 0 || header.height == 0) return std::nullopt;
    if (std::fseek(f, 4, SEEK_CUR) != 0) return std::nullopt; // IHDR's CRC
    // What the chunks before the pixels say of their values. An sRGB chunk makes them sRGB whatever
    // else is there (OpenImageIO's reader looks at it first); gAMA and cHRM are allowed beside it
    // with sRGB's own values, as OpenImageIO's writer and libpng's png_set_sRGB_gAMA_and_cHRM put
    // them, so that libpng finds nothing to reconcile.
    bool srgb = false, gamma_or_chromaticities = false, not_srgbs = false;
    // A file's chunks before its pixels are few; one with thousands is the codecs' to read.
    for (int chunk = 0; chunk < 1000; ++chunk) {
        std::array<unsigned char, 8> head{};
        if (std::fread(head.data(), 1, head.size(), f) != head.size()) return std::nullopt;
        const std::uint32_t length = big_endian(head.data());
        const std::string_view type(reinterpret_cast<const char*>(head.data() + 4), 4);
        if (type == "IDAT") {
            if (gamma_or_chromaticities && (!srgb || not_srgbs)) return std::nullopt;
            return header;
        }
        for (std::string_view decoding : {"iCCP", "sBIT", "tRNS", "PLTE"})
            if (type == decoding) return std::nullopt;
        if (length > 0x7fffffffu) return std::nullopt;
        std::uint32_t skipped = length;
        if (type == "sRGB") srgb = true;
        // OpenImageIO takes a text chunk's keyword and text as an attribute of the image, after the
        // color space it found: "oiio:ColorSpace" other than sRGB (its writer's own, for lin_srgb,
        // raw, ...) says the values are other than sRGB. kdop's PNGs say "sRGB" there. The
        // keyword is the chunk's first field; tEXt's text follows it, uncompressed.
        if (type == "tEXt" || type == "zTXt" || type == "iTXt") {
            std::array<char, 64> start_of_text{};
            const std::uint32_t size = std::min<std::uint32_t>(length, start_of_text.size());
            if (std::fread(start_of_text.data(), 1, size, f) != size) return std::nullopt;
            skipped = length - size;
            std::string text(start_of_text.data(), size);
            std::ranges::transform(text, text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
            if (text.starts_with("oiio:") && !(type == "tEXt" && text == std::string("oiio:colorspace\0srgb", 20)))
                return std::nullopt;
        }
        if (type == "gAMA" || type == "cHRM") {
            // sRGB's gamma (1/2.2 in units of 100000) and its primaries and white point (Rec. 709, D65).
            static constexpr std::array<std::uint32_t, 8> kSrgbChromaticities{31270, 32900, 64000, 33000,
                                                                              30000, 60000, 15000, 6000};
            std::array<unsigned char, 32> data{};
            const std::size_t size = type == "gAMA" ? 4 : 32;
            if (length != size || std::fread(data.data(), 1, size, f) != size) return std::nullopt;
            skipped = 0;
            gamma_or_chromaticities = true;
            if (type == "gAMA") not_srgbs = not_srgbs || big_endian(data.data()) != 45455;
            for (std::size_t i = 0; type == "cHRM" && i < kSrgbChromaticities.size(); ++i)
                not_srgbs = not_srgbs || big_endian(data.data() + 4 * i) != kSrgbChromaticities[i];
        }
        if (std::fseek(f, long(skipped) + 4, SEEK_CUR) != 0) return std::nullopt; // the data left, and the CRC
    }
    return std::nullopt;
}

bool named_png(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::ranges::transform(extension, extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".png";
}

} // namespace

std::optional<Result<Image>> read_plain_png(const std::string& file, const ImageRead& read) {
    const std::string& path = read.name.empty() ? file : read.name;
    if (read.corner != glm::uvec2(0, 0) || !named_png(path)) return std::nullopt;
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
    if (!f) return std::nullopt;
    const std::optional<PlainHeader> header = plain_header(f.get());
    if (!header || header->channels < read.needed || std::fseek(f.get(), 0, SEEK_SET) != 0) return std::nullopt;

    // libpng's simplified API reports its errors in the image, with no longjmp through kdop's code.
    // A header it refuses (a side beyond its limit, an unknown method, a bad CRC) is the codecs'
    // to report.
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_stdio(&png, f.get())) {
        png_image_free(&png);
        return std::nullopt;
    }
    // As stored: a plain PNG's 8-bit sRGB values and straight alpha are the simplified API's own.
    png.format = header->channels == 4 ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
    if (png.width != header->width || png.height != header->height) {
        png_image_free(&png);
        return std::nullopt;
    }
    // The codecs' checks, in their words, on a header libpng has accepted.
    auto refused = [&](Error error) {
        png_image_free(&png);
        return std::optional<Result<Image>>(std::unexpected(std::move(error)));
    };
    if (auto ok = check_max_side(path, header->width, header->height, read.max_side); !ok) return refused(ok.error());
    if (auto ok = check_memory(fmt::format("{}: a {}x{} image", path, header->width, header->height),
                               whole_read_bytes(header->width, header->height, header->channels));
        !ok)
        return refused(ok.error());
    std::vector<std::uint8_t> stored(PNG_IMAGE_SIZE(png));
    if (!png_image_finish_read(&png, nullptr, stored.data(), 0, nullptr)) {
        png_image_free(&png);
        return std::nullopt;
    }

    // Each of the 256 values as the codecs convert it (OpenImageIO's v * (1/255)), color decoded
    // from sRGB unless the read says the values are linear.
    std::array<float, 256> as_value{}, as_color{};
    for (int v = 0; v < 256; ++v) {
        as_value[std::size_t(v)] = float(v) * (1.0f / 255.0f);
        as_color[std::size_t(v)] =
            read.space == InputSpace::linear ? as_value[std::size_t(v)] : srgb_to_linear(as_value[std::size_t(v)]);
    }
    Image image(header->width, header->height);
    const int channels = header->channels;
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < channels; ++c) {
            const std::uint8_t v = stored[i * std::size_t(channels) + std::size_t(c)];
            image.pixels[i][c] = c < 3 ? as_color[v] : as_value[v];
        }
    return image;
}

} // namespace kdop
