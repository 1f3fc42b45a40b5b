// Writing images: what is written reads back as written, or the write is an error and leaves no
// file. A full disk (a 64 KiB tmpfs, where the system lets the test mount one) used to pass
// silently through OpenImageIO's PNG, BMP and TGA writers.
#include "image_io.h"
#include "random.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

namespace kdop {
namespace {
namespace fs = std::filesystem;

// Noise, so no format compresses it below the 64 KiB the full-disk test leaves room for.
Image noise(std::uint32_t size, float scale) {
    Image image(size, size);
    Random random(7);
    for (glm::vec4& p : image.pixels)
        p = {float(random.uniform()) * scale, float(random.uniform()) * scale, float(random.uniform()) * scale, 1};
    return image;
}

// A 64 KiB tmpfs mounted for the test's lifetime; empty where mounting is not allowed here.
struct SmallDisk {
    test::TempDir dir;
    fs::path path = dir / "small";
    bool mounted = false;
    SmallDisk() {
        fs::create_directories(path);
        mounted = test::run("mount -t tmpfs -o size=64k tmpfs " + path.string() + " 2>/dev/null").exit_code == 0;
    }
    ~SmallDisk() {
        if (mounted) test::run("umount " + path.string());
    }
};

TEST(ImageIo, AFullDiskIsAnErrorAndLeavesNoFile) {
    SmallDisk disk;
    if (!disk.mounted) GTEST_SKIP() << "cannot mount a tmpfs here (needs root); the full-disk check did not run";
    const Image image = noise(256, 1.0f); // 1 MiB as floats, 192-256 KiB in 8-bit formats
    for (const char* ext : {"png", "bmp", "tga", "exr", "tif"}) {
        const fs::path out = disk.path / (std::string("out.") + ext);
        auto written = write_image(out.string(), image);
        EXPECT_FALSE(written) << ext << " reported success on a full disk";
        if (!written) {
            EXPECT_NE(written.error().message.find(out.string()), std::string::npos) << written.error().message;
        }
        EXPECT_TRUE(fs::is_empty(disk.path)) << ext << " left a file behind";
    }
}

TEST(ImageIo, WhatIsWrittenReadsBackAsWritten) {
    test::TempDir dir;
    const Image ldr = noise(16, 1.0f), hdr = noise(16, 6e4f);
    struct Case {
        const char* ext;
        const Image& image;
        double tolerance; // absolute for 8-bit, relative for the float formats
    };
    for (const Case& c : {Case{"exr", hdr, 0.0}, Case{"tif", hdr, 0.0}, Case{"hdr", hdr, 1.0 / 64},
                          Case{"png", ldr, 0.51 / 255}, Case{"bmp", ldr, 0.51 / 255}, Case{"tga", ldr, 0.51 / 255}}) {
        const std::string path = (dir / (std::string("round.") + c.ext)).string();
        auto written = write_image(path, c.image);
        ASSERT_TRUE(written) << c.ext << ": " << written.error().message;
        auto read = read_image(path);
        ASSERT_TRUE(read) << read.error().message;
        const std::string ext = c.ext;
        double worst = 0;
        for (std::size_t i = 0; i < read->pixels.size(); ++i) {
            const glm::vec4& p = c.image.pixels[i];
            for (int ch = 0; ch < 3; ++ch) {
                const double expected = p[ch], got = read->pixels[i][ch];
                // 8-bit: absolute; float: relative to the value; RGBE: to the pixel's largest channel.
                const double scale = ext == "png" || ext == "bmp" || ext == "tga" ? 1.0
                                     : ext == "hdr"                               ? double(std::max({p.r, p.g, p.b}))
                                                                                  : std::max(1.0, std::abs(expected));
                worst = std::max(worst, std::abs(got - expected) / scale);
            }
        }
        EXPECT_LE(worst, c.tolerance) << c.ext;
    }
}

// Transparency, negative and non-finite values survive where the format can hold them: color is
// stored unassociated (not divided by alpha), so PNG and TGA give back the transparent pixels as
// written; EXR and TIFF give back everything, NaN and infinity included.
TEST(ImageIo, TransparentNegativeAndNonFinitePixelsWriteAndReadBack) {
    test::TempDir dir;
    Image image(4, 1);
    image.pixels = {{0.5f, 0.25f, 0.75f, 0.0f},
                    {0.8f, 0.6f, 0.4f, 0.5f},
                    {-2.0f, 3e4f, 0.1f, 1.0f},
                    {NAN, INFINITY, -INFINITY, 1.0f}};
    Image transparent(2, 1);
    transparent.pixels = {image.pixels[0], image.pixels[1]};
    for (const char* ext : {"exr", "tif", "png", "tga"}) {
        const std::string path = (dir / (std::string("alpha.") + ext)).string();
        const bool floats = std::string(ext) == "exr" || std::string(ext) == "tif";
        auto written = write_image(path, floats ? image : transparent);
        ASSERT_TRUE(written) << ext << ": " << written.error().message;
        auto read = read_image(path);
        ASSERT_TRUE(read) << read.error().message;
        for (std::size_t i = 0; i < 2; ++i) // the transparent pixels keep their color
            for (int c = 0; c < 4; ++c)
                EXPECT_NEAR(read->pixels[i][c], image.pixels[i][c], floats ? 0.0 : 0.51 / 255) << ext << " " << i;
        if (floats) {
            EXPECT_EQ(read->pixels[2], image.pixels[2]) << ext;
            EXPECT_TRUE(std::isnan(read->pixels[3].r)) << ext;
            EXPECT_EQ(read->pixels[3].g, INFINITY) << ext;
        }
    }
    auto hdr = write_image((dir / "signed.hdr").string(), image);
    ASSERT_FALSE(hdr);
    EXPECT_NE(hdr.error().message.find("Radiance HDR cannot hold negative or non-finite values"), std::string::npos)
        << hdr.error().message;
}

// PNG, BMP and TGA store 0..1: an image with anything else is refused with the first such value, not
// clamped, and nothing is written.
TEST(ImageIo, IntegerFormatsRefuseValuesTheyWouldClamp) {
    test::TempDir dir;
    for (float value : {1.5f, -0.25f, NAN, INFINITY})
        for (const char* ext : {"png", "bmp", "tga"}) {
            Image image(3, 2, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
            image.at(2, 1).g = value;
            const fs::path path = dir / (std::string("out.") + ext);
            auto written = write_image(path.string(), image);
            ASSERT_FALSE(written) << ext << " " << value;
            EXPECT_NE(written.error().message.find("pixel (2, 1) holds"), std::string::npos) << written.error().message;
            EXPECT_TRUE(fs::is_empty(dir.path())) << ext << " left a file";
        }
}

// kdop's values are linear. A PNG holding them must say so (gAMA 1.0, no sRGB chunk); untagged, a
// viewer would decode them as sRGB and show them too dark.
TEST(ImageIo, PngSaysItsValuesAreLinear) {
    test::TempDir dir;
    const fs::path path = dir / "linear.png";
    ASSERT_TRUE(write_image(path.string(), Image(2, 2, glm::vec4(0.25f, 0.5f, 0.75f, 1.0f))));
    const std::string bytes = test::read_file(path);
    std::optional<std::uint32_t> gamma;
    bool srgb = false;
    for (std::size_t at = 8; at + 12 <= bytes.size();) { // chunks: length, type, data, CRC
        auto word = [&](std::size_t i) {
            return std::uint32_t(std::uint8_t(bytes[i])) << 24 | std::uint32_t(std::uint8_t(bytes[i + 1])) << 16 |
                   std::uint32_t(std::uint8_t(bytes[i + 2])) << 8 | std::uint8_t(bytes[i + 3]);
        };
        const std::string type = bytes.substr(at + 4, 4);
        if (type == "gAMA") gamma = word(at + 8);
        srgb |= type == "sRGB" || type == "iCCP";
        at += 12 + word(at);
    }
    ASSERT_TRUE(gamma) << "no gAMA chunk";
    EXPECT_EQ(*gamma, 100000u) << "gAMA stores 1/gamma x 100000; linear is 100000";
    EXPECT_FALSE(srgb);
    auto back = read_image(path.string());
    ASSERT_TRUE(back);
    EXPECT_EQ(back->at(1, 1), glm::vec4(64 / 255.0f, 128 / 255.0f, 191 / 255.0f, 1.0f)) << "read as stored";
}

// The image fuzzer's first finding: libpng's error for a damaged stream spans two lines.
TEST(ImageIo, AReadersErrorIsOneLineOfPrintableText) {
    auto image = read_image(test::data_path("damaged-idat.png"));
    ASSERT_FALSE(image);
    const std::string& message = image.error().message;
    EXPECT_NE(message.find("damaged-idat.png: cannot read pixels: PNG read error"), std::string::npos) << message;
    EXPECT_TRUE(std::none_of(message.begin(), message.end(), [](char c) { return (unsigned char)c < 0x20; }))
        << message;
}

// The image fuzzer's second finding: OpenImageIO's BMP reader throws std::length_error from open()
// for this 58-byte RLE file, which reached the command line as "kdop: vector::_M_default_append".
TEST(ImageIo, AReaderThatThrowsIsAnErrorNamingTheFile) {
    auto image = read_image(test::data_path("bmp-rle-overrun.bmp"));
    ASSERT_FALSE(image);
    EXPECT_NE(image.error().message.find("bmp-rle-overrun.bmp: cannot read image: "), std::string::npos)
        << image.error().message;
}

TEST(ImageIo, LossyFormatsAreRefusedBeforeAnythingIsWritten) {
    test::TempDir dir;
    auto written = write_image((dir / "out.jpg").string(), noise(8, 1.0f));
    ASSERT_FALSE(written);
    EXPECT_NE(written.error().message.find("jpeg is lossy"), std::string::npos) << written.error().message;
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

} // namespace
} // namespace kdop
