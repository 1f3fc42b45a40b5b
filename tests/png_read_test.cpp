// Plain PNGs, read by libpng without the codecs' module (images/png_read.h): every pixel is the
// codecs' own, bit for bit, in every input space and for data; any PNG that is not plain is left
// to the codecs, and the module's table refuses a caller of another build. Found by review: a text
// chunk "oiio:ColorSpace" and an interlaced file cut short after its pixels.
#include "images/image_codecs.h"
#include "images/oiio_codecs.h"
#include "images/png_read.h"
#include "images/random.h"
#include "tests/test_support.h"

#include <dlfcn.h>
#include <glm/vec3.hpp>
#include <gtest/gtest.h>
#include <png.h>

#include <bit>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <filesystem>

namespace kdop {
namespace {
namespace fs = std::filesystem;

// How the test file is made: its bit depth, color type and the chunks that say how to decode it.
struct PngKind {
    const char* name;
    int depth = 8, color_type = PNG_COLOR_TYPE_RGB;
    bool interlaced = false, srgb_chunk = false;
    double gamma = 0;                           // a gAMA chunk's, where not 0
    bool srgb_gamma_and_chromaticities = false; // sRGB, gAMA and cHRM, as OpenImageIO writes them
    bool transparent_color = false;
    const char* text_key = nullptr; // a tEXt chunk's keyword, where given
    const char* text = "";
};

// A width x height PNG of `kind` holding every value of its depth in each channel, written with
// libpng's own writer (not OpenImageIO's, which writes no interlaced file).
void write_png(const fs::path& path, const PngKind& kind, std::uint32_t width, std::uint32_t height) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_TRUE(f);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    const int channels = kind.color_type == PNG_COLOR_TYPE_RGB_ALPHA ? 4
                         : kind.color_type == PNG_COLOR_TYPE_RGB     ? 3
                         : kind.color_type == PNG_COLOR_TYPE_GRAY    ? 1
                                                                     : 1; // palette indices
    const std::size_t bytes = kind.depth / 8;
    std::vector<png_byte> data(std::size_t(width) * height * channels * bytes);
    Random random(11);
    const std::uint32_t levels = kind.color_type == PNG_COLOR_TYPE_PALETTE ? 4 : 1u << kind.depth;
    for (std::size_t i = 0; i < data.size() / bytes; ++i) {
        const std::uint32_t v = std::uint32_t(i < levels ? i : random.uniform() * levels) % levels;
        for (std::size_t b = 0; b < bytes; ++b) data[i * bytes + b] = png_byte(v >> (8 * (bytes - 1 - b)));
    }
    std::vector<png_bytep> rows(height);
    for (std::uint32_t y = 0; y < height; ++y) rows[y] = data.data() + std::size_t(y) * width * channels * bytes;
    if (setjmp(png_jmpbuf(png)) == 0) {
        png_init_io(png, f);
        png_set_IHDR(png, info, width, height, kind.depth, kind.color_type,
                     kind.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                     PNG_FILTER_TYPE_DEFAULT);
        if (kind.color_type == PNG_COLOR_TYPE_PALETTE) {
            png_color palette[4] = {{0, 0, 0}, {255, 0, 0}, {0, 128, 0}, {10, 20, 250}};
            png_set_PLTE(png, info, palette, 4);
        }
        if (kind.srgb_chunk) png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
        if (kind.gamma > 0) png_set_gAMA(png, info, kind.gamma);
        if (kind.srgb_gamma_and_chromaticities) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
        if (kind.text_key) {
            png_text text{};
            text.compression = PNG_TEXT_COMPRESSION_NONE;
            text.key = const_cast<char*>(kind.text_key);
            text.text = const_cast<char*>(kind.text);
            png_set_text(png, info, &text, 1);
        }
        if (kind.transparent_color) {
            png_color_16 transparent{0, 0, 0, 0, 0};
            png_set_tRNS(png, info, nullptr, 0, &transparent);
        }
        png_write_info(png, info);
        if (kind.interlaced) png_set_interlace_handling(png);
        png_write_image(png, rows.data());
        png_write_end(png, nullptr);
    } else {
        ADD_FAILURE() << "libpng could not write " << path;
    }
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
}

bool same_bits(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) return false;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 4; ++c)
            if (std::bit_cast<std::uint32_t>(a.pixels[i][c]) != std::bit_cast<std::uint32_t>(b.pixels[i][c]))
                return false;
    return true;
}

TEST(PlainPng, EveryPixelIsTheCodecs) {
    test::TempDir dir;
    const PngKind plain[] = {
        {.name = "rgb"},
        {.name = "rgba", .color_type = PNG_COLOR_TYPE_RGB_ALPHA},
        {.name = "rgb-srgb", .srgb_chunk = true},
        {.name = "rgb-srgb-gamma-chromaticities", .srgb_gamma_and_chromaticities = true},
        {.name = "rgb-software", .text_key = "Software", .text = "a renderer"},
    };
    const ImageRead reads[] = {
        {.space = InputSpace::from_file},
        {.space = InputSpace::linear},
        {.space = InputSpace::srgb},
        {.space = InputSpace::linear, .needed = 2}, // data
    };
    std::vector<fs::path> files;
    for (const PngKind& kind : plain) {
        files.push_back(dir / (std::string(kind.name) + ".png"));
        write_png(files.back(), kind, 37, 29);
    }
    // kdop's own PNGs, opaque (RGB) and not.
    Image picture(23, 17);
    Random random(5);
    for (glm::vec4& p : picture.pixels) p = glm::vec4(random.uniform(), random.uniform(), random.uniform(), 1);
    files.push_back(dir / "kdop-rgb.png");
    ASSERT_TRUE(write_image(files.back().string(), picture));
    picture.pixels[7].a = 0.5f;
    files.push_back(dir / "kdop-rgba.png");
    ASSERT_TRUE(write_image(files.back().string(), picture));
    for (const fs::path& path : files) {
        const std::string name = path.filename().string();
        for (const ImageRead& read : reads) {
            const auto fast = read_plain_png(path.string(), read);
            ASSERT_TRUE(fast) << name << " was left to the codecs";
            ASSERT_TRUE(*fast) << fast->error().message;
            const auto codecs = oiio::read(path.string(), read);
            ASSERT_TRUE(codecs) << codecs.error().message;
            EXPECT_TRUE(same_bits(**fast, *codecs)) << name << ", input space " << int(read.space);
        }
    }
}

TEST(PlainPng, AnyOtherPngIsLeftToTheCodecs) {
    test::TempDir dir;
    const PngKind others[] = {
        {.name = "rgb16", .depth = 16},
        {.name = "gray", .color_type = PNG_COLOR_TYPE_GRAY},
        {.name = "palette", .color_type = PNG_COLOR_TYPE_PALETTE},
        {.name = "linear", .gamma = 1.0},
        {.name = "gamma-2.2", .gamma = 1 / 2.2}, // OpenImageIO: GammaCorrected2.2, not sRGB
        {.name = "transparent-black", .transparent_color = true},
        // OpenImageIO's reader refuses one cut short after its pixels; libpng's simplified API does not.
        {.name = "rgba-interlaced", .color_type = PNG_COLOR_TYPE_RGB_ALPHA, .interlaced = true},
        // OpenImageIO's writer says so for lin_srgb, raw, ...: values as stored, not sRGB.
        {.name = "linear-by-text", .text_key = "oiio:ColorSpace", .text = "lin_srgb"},
    };
    for (const PngKind& kind : others) {
        const fs::path path = dir / (std::string(kind.name) + ".png");
        write_png(path, kind, 19, 11);
        EXPECT_FALSE(read_plain_png(path.string(), {})) << kind.name;
        // And read as the codecs read it, or refused as they refuse it.
        const auto read = read_image(path.string()), codecs = oiio::read(path.string(), {});
        ASSERT_EQ(bool(read), bool(codecs)) << kind.name;
        if (read) {
            EXPECT_TRUE(same_bits(*read, *codecs)) << kind.name;
        }
    }
    // A plain PNG by another extension, and a corner, are the codecs' too.
    write_png(dir / "rgb.png", {.name = "rgb"}, 19, 11);
    fs::copy_file(dir / "rgb.png", dir / "rgb.tga");
    EXPECT_FALSE(read_plain_png((dir / "rgb.tga").string(), {}));
    EXPECT_FALSE(read_plain_png((dir / "rgb.png").string(), {.corner = {4, 4}}));
    // A device smaller than the image, in the codecs' words.
    auto small = read_plain_png((dir / "rgb.png").string(), {.max_side = 16});
    ASSERT_TRUE(small && !*small);
    EXPECT_EQ(small->error().message, oiio::read((dir / "rgb.png").string(), {.max_side = 16}).error().message);
}

TEST(PlainPng, ADamagedPlainPngIsTheCodecsToReport) {
    test::TempDir dir;
    write_png(dir / "rgb.png", {.name = "rgb"}, 64, 64);
    std::string bytes = test::read_file(dir / "rgb.png");
    bytes.resize(bytes.size() - 40); // cut inside IDAT
    test::write_file(dir / "cut.png", bytes);
    EXPECT_FALSE(read_plain_png((dir / "cut.png").string(), {}));
    auto read = read_image((dir / "cut.png").string());
    ASSERT_FALSE(read);
    EXPECT_NE(read.error().message.find("cut.png: cannot read pixels"), std::string::npos) << read.error().message;
}

// A PNG whose gAMA chunk says 1/2.2, without sRGB's chunk (as GIMP and ImageMagick write it), holds
// values to the power 2.2, not sRGB: OpenImageIO 2.4 tags it "Gamma2.2", which kdop read as sRGB
// until review found it.
TEST(PlainPng, AGammaChunkIsAPower) {
    test::TempDir dir;
    const fs::path path = dir / "gamma.png";
    write_png(path, {.name = "gamma", .gamma = 1 / 2.2}, 4, 1);
    auto image = read_image(path.string());
    ASSERT_TRUE(image) << image.error().message;
    // The first pixels hold 0, 1, 2, ... in turn (write_png).
    for (int c = 0; c < 3; ++c) {
        const float stored = float(3 + c) * (1.0f / 255.0f);
        EXPECT_EQ(image->at(1, 0)[c], std::pow(stored, 2.2f)) << c;
    }
}

// The module beside the test binary gives its table to this build alone.
TEST(ImageCodecs, TheModuleServesItsOwnBuildAlone) {
    const fs::path module = fs::path(KDOP_CLI_PATH).parent_path() / "kdop_image_codecs.so";
    void* handle = dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
    ASSERT_TRUE(handle) << dlerror();
    const auto entry = reinterpret_cast<ImageCodecsEntry>(dlsym(handle, kImageCodecsEntry));
    ASSERT_TRUE(entry);
    EXPECT_TRUE(entry(image_codecs_build().c_str()));
    EXPECT_FALSE(entry("0.0.1, table 1 of 40 bytes"));
    EXPECT_FALSE(entry(nullptr));
    auto loaded = image_codecs();
    ASSERT_TRUE(loaded) << loaded.error().message;
    EXPECT_EQ(*loaded, entry(image_codecs_build().c_str())) << "one module, loaded once";
}

// kdop starts without OpenImageIO's libraries, and loads them for the first file they read: not
// for a plain PNG pair, for an EXR pair.
TEST(CliStartUp, TheCodecsAreLoadedForTheFirstFileTheyRead) {
    const std::string kdop = test::shell_word(test::kdop_binary());
    auto traced = test::run("LD_TRACE_LOADED_OBJECTS=1 " + kdop);
    ASSERT_EQ(traced.exit_code, 0) << traced.err;
    EXPECT_NE(traced.out.find("libvulkan"), std::string::npos) << traced.out;
    EXPECT_EQ(traced.out.find("OpenImageIO"), std::string::npos) << traced.out;

    test::TempDir dir;
    Image reference(48, 32), test_image(48, 32);
    Random random(3);
    for (std::size_t i = 0; i < reference.pixels.size(); ++i) {
        reference.pixels[i] = glm::vec4(float(random.uniform()), float(random.uniform()), float(random.uniform()), 1);
        test_image.pixels[i] = glm::vec4(glm::vec3(reference.pixels[i]) * 0.9f, 1);
    }
    std::string means;
    for (const char* extension : {".png", ".exr"}) {
        const fs::path ref = dir / (std::string("reference") + extension),
                       tst = dir / (std::string("test") + extension);
        ASSERT_TRUE(write_image(ref.string(), reference));
        ASSERT_TRUE(write_image(tst.string(), test_image));
        auto flip = test::run("LD_DEBUG=files " + kdop + " flip --cpu --reference " + test::shell_word(ref.string()) +
                              " --test " + test::shell_word(tst.string()));
        ASSERT_EQ(flip.exit_code, 0) << flip.err;
        EXPECT_EQ(flip.err.find("kdop_image_codecs.so") != std::string::npos, std::string(extension) == ".exr")
            << extension << "\n"
            << flip.err.substr(0, 4000);
        EXPECT_NE(flip.out.find("LDR-FLIP mean"), std::string::npos) << flip.out;
    }
}

} // namespace
} // namespace kdop
