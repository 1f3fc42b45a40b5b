// Writing images: what is written reads back as written, or the write is an error and leaves no
// file. A full disk (a 64 KiB tmpfs, where the system lets the test mount one) used to pass
// silently through OpenImageIO's PNG, BMP and TGA writers.
#include "core/write_files.h"
#include "images/image_io.h"
#include "images/random.h"
#include "images/srgb.h"
#include "images/srgb_bytes.h"
#include "tests/test_support.h"

#include <OpenImageIO/imageio.h>
#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <optional>
#include <tuple>

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
            EXPECT_NE(written.error().message.find("the disk is full"), std::string::npos) << written.error().message;
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
        double tolerance; // absolute in the sRGB-encoded values for 8-bit, relative for the float formats
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
            const bool eight_bit = ext == "png" || ext == "bmp" || ext == "tga";
            for (int ch = 0; ch < 3; ++ch) {
                // 8-bit files hold sRGB-encoded values: within half a step of them once encoded again.
                const double expected = eight_bit ? linear_to_srgb(p[ch]) : p[ch];
                const double got = eight_bit ? linear_to_srgb(read->pixels[i][ch]) : read->pixels[i][ch];
                // 8-bit: absolute; float: relative to the value; RGBE: to the pixel's largest channel.
                const double scale = eight_bit      ? 1.0
                                     : ext == "hdr" ? double(std::max({p.r, p.g, p.b}))
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
        // The transparent pixels keep their color (8-bit: within half a step of the sRGB-encoded value).
        auto stored = [&](float v, int c) { return floats || c == 3 ? v : linear_to_srgb(v); };
        for (std::size_t i = 0; i < 2; ++i)
            for (int c = 0; c < 4; ++c)
                EXPECT_NEAR(stored(read->pixels[i][c], c), stored(image.pixels[i][c], c), floats ? 0.0 : 0.51 / 255)
                    << ext << " " << i;
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

// An opaque PNG is stored as RGB (a quarter fewer bytes to compress) and reads back with alpha 1;
// one transparent pixel keeps the alpha channel. The bytes read back are those written either way.
TEST(ImageIo, AnOpaquePngLeavesItsAlphaOut) {
    test::TempDir dir;
    Image image(64, 48);
    Random rng(7);
    for (glm::vec4& p : image.pixels)
        p = glm::vec4(float(rng.uniform()), float(rng.uniform()), float(rng.uniform()), 1.0f);
    Image transparent = image;
    transparent.at(63, 47).a = 0.5f;
    for (const auto& [name, written, channels] :
         {std::tuple{"opaque.png", &image, 3}, std::tuple{"transparent.png", &transparent, 4}}) {
        const std::string path = (dir / name).string();
        ASSERT_TRUE(write_image(path, *written));
        auto in = OIIO::ImageInput::open(path);
        ASSERT_TRUE(in);
        EXPECT_EQ(in->spec().nchannels, channels) << name;
        auto read = read_image(path);
        ASSERT_TRUE(read) << read.error().message;
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
            EXPECT_NEAR(read->pixels[i].a, written->pixels[i].a, 0.51 / 255) << name; // 1 exactly where opaque
            if (written->pixels[i].a == 1.0f) {
                EXPECT_EQ(read->pixels[i].a, 1.0f) << name;
            }
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(linear_to_srgb(read->pixels[i][c]), linear_to_srgb(written->pixels[i][c]), 0.51 / 255)
                    << name << " pixel " << i;
        }
    }
}

// Data (motion, depth) is written with only the channels it uses, as floats under the names given,
// and read_data_image gives back every value bit for bit; a format that does not keep floats is
// refused, naming the file.
TEST(ImageIo, DataImagesKeepOnlyTheirChannelsAsFloats) {
    test::TempDir dir;
    Image motion(5, 3);
    Random rng(11);
    for (glm::vec4& p : motion.pixels)
        p = glm::vec4(float(rng.uniform(-300, 300)), float(rng.uniform(-1e-3, 1e-3)), 7.0f, 9.0f);
    for (const auto& [name, channels] : {std::pair{"motion.exr", std::vector<const char*>{"R", "G"}},
                                         std::pair{"depth.exr", std::vector<const char*>{"Z"}},
                                         std::pair{"depth.tif", std::vector<const char*>{"Z"}}}) {
        const fs::path path = dir / name;
        ASSERT_TRUE(write_atomically(
            {{path, [&](const fs::path& to) { return write_data_image_to(to, path.string(), motion, channels); }}}))
            << name;
        auto in = OIIO::ImageInput::open(path.string());
        ASSERT_TRUE(in) << name;
        EXPECT_EQ(in->spec().nchannels, int(channels.size())) << name;
        EXPECT_EQ(in->spec().format, OIIO::TypeDesc::FLOAT) << name;
        auto read = read_data_image(path.string(), int(channels.size()));
        ASSERT_TRUE(read) << read.error().message;
        for (std::size_t i = 0; i < motion.pixels.size(); ++i)
            for (std::size_t c = 0; c < 4; ++c)
                EXPECT_EQ(read->pixels[i][int(c)], c < channels.size() ? motion.pixels[i][int(c)]
                                                   : c == 3            ? 1.0f
                                                                       : 0.0f)
                    << name << " pixel " << i << " channel " << c;
    }
    const fs::path png = dir / "motion.png";
    const char* const two[] = {"R", "G"};
    auto refused = write_atomically(
        {{png, [&](const fs::path& to) { return write_data_image_to(to, png.string(), motion, two); }}});
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("motion.png: png does not keep the floats data holds; write EXR"),
              std::string::npos)
        << refused.error().message;
    EXPECT_FALSE(fs::exists(png));
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

// kdop's values are linear; a PNG holds them sRGB-encoded, as every viewer expects, and says so
// (its sRGB chunk).
TEST(ImageIo, PngHoldsSrgbAndSaysSo) {
    test::TempDir dir;
    const fs::path path = dir / "picture.png";
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
    EXPECT_TRUE(srgb) << "no sRGB chunk";
    if (gamma) {
        EXPECT_EQ(*gamma, 45455u) << "gAMA, if any, must agree: 1/2.2 x 100000";
    }
    // The bytes are the encoded values: 0.25, 0.5, 0.75 become 137, 188, 225.
    auto stored = read_image(path.string(), 0, InputSpace::linear);
    auto back = read_image(path.string());
    ASSERT_TRUE(stored) << stored.error().message;
    ASSERT_TRUE(back) << back.error().message;
    const int bytes_expected[3] = {137, 188, 225};
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(std::lround(stored->at(1, 1)[c] * 255), bytes_expected[c]) << "as stored, channel " << c;
        EXPECT_NEAR(back->at(1, 1)[c], srgb_to_linear(bytes_expected[c] / 255.0f), 1e-6)
            << "decoded to linear as the file says, channel " << c;
    }
}

// Each file is decoded as it says: 8-bit PNG untagged or sRGB from sRGB, a PNG tagged linear (what
// kdop wrote before) as stored, a gamma-tagged one by its power, EXR always as stored; --input-space
// overrides.
TEST(ImageIo, EachFileIsDecodedAsItSays) {
    test::TempDir dir;
    auto write_tagged = [&](const std::string& name, const char* color_space, float gamma) {
        const std::string path = (dir / name).string();
        auto out = OIIO::ImageOutput::create(path);
        OIIO::ImageSpec spec(1, 1, 3, OIIO::TypeDesc::UINT8);
        if (color_space) spec.attribute("oiio:ColorSpace", color_space);
        if (gamma > 0) spec.attribute("oiio:Gamma", gamma);
        const std::uint8_t pixel[3] = {64, 128, 255};
        EXPECT_TRUE(out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, pixel) && out->close());
        return path;
    };
    const glm::vec3 stored(64 / 255.0f, 128 / 255.0f, 1.0f);
    const glm::vec3 srgb(srgb_to_linear(stored.r), srgb_to_linear(stored.g), 1.0f);
    auto read = [](const std::string& path, InputSpace space = InputSpace::from_file) {
        return glm::vec3(read_image(path, 0, space)->at(0, 0));
    };
    EXPECT_EQ(read(write_tagged("untagged.png", nullptr, 0)), srgb);
    EXPECT_EQ(read(write_tagged("srgb.png", "sRGB", 0)), srgb);
    EXPECT_EQ(read(write_tagged("untagged.bmp", nullptr, 0)), srgb);
    const std::string linear = write_tagged("linear.png", "linear", 0);
    EXPECT_EQ(read(linear), stored);
    EXPECT_EQ(read(linear, InputSpace::srgb), srgb) << "--input-space srgb overrides the tag";
    const glm::vec3 gamma = read(write_tagged("gamma.png", "GammaCorrected2.2", 2.2f));
    EXPECT_NEAR(gamma.g, std::pow(stored.g, 2.2f), 1e-3f);
    const std::string exr = (dir / "values.exr").string();
    ASSERT_TRUE(write_image(exr, Image(1, 1, glm::vec4(0.25f, 0.5f, 2.0f, 1.0f))));
    EXPECT_EQ(read(exr), glm::vec3(0.25f, 0.5f, 2.0f));
    EXPECT_EQ(read(exr, InputSpace::linear), glm::vec3(0.25f, 0.5f, 2.0f));
    EXPECT_EQ(parse_input_space("srgb"), InputSpace::srgb);
    EXPECT_FALSE(parse_input_space("sRGB-ish"));
}

// 8- and 16-bit files are decoded through a table of every value a channel holds: the pixels must
// be those of OpenImageIO's float read decoded value by value, bit for bit, color and alpha.
TEST(ImageIo, IntegerFilesDecodeAsTheirFloatReadDoes) {
    test::TempDir dir;
    auto check = [&](const std::string& name, OIIO::TypeDesc type, const char* color_space, InputSpace space,
                     auto decode) {
        const std::string path = (dir / name).string();
        const int size = type == OIIO::TypeDesc::UINT16 ? 256 : 16; // every value of the type, in each channel
        std::vector<std::uint16_t> values(std::size_t(size) * size * 4);
        for (std::size_t i = 0; i < values.size(); ++i)
            values[i] = std::uint16_t((i / 4 + 37 * (i % 4)) % (size * size));
        auto out = OIIO::ImageOutput::create(path);
        OIIO::ImageSpec spec(size, size, 4, type);
        if (color_space) spec.attribute("oiio:ColorSpace", color_space);
        ASSERT_TRUE(out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT16, values.data()) && out->close());
        OIIO::ImageSpec as_stored; // alpha not multiplied in, as kdop reads it
        as_stored.attribute("oiio:UnassociatedAlpha", 1);
        auto in = OIIO::ImageInput::open(path, &as_stored);
        std::vector<float> floats(values.size());
        ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, floats.data()));
        auto image = read_image(path, 0, space);
        ASSERT_TRUE(image) << image.error().message;
        for (std::size_t i = 0; i < floats.size(); ++i) {
            const float expected = i % 4 < 3 ? decode(floats[i]) : floats[i];
            ASSERT_EQ(std::bit_cast<std::uint32_t>(image->pixels[i / 4][int(i % 4)]),
                      std::bit_cast<std::uint32_t>(expected))
                << name << " value " << i;
        }
    };
    auto srgb = [](float v) { return srgb_to_linear(v); };
    auto linear = [](float v) { return v; };
    for (OIIO::TypeDesc type : {OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT16}) {
        const std::string bits = type == OIIO::TypeDesc::UINT8 ? "8" : "16";
        check(bits + "-srgb.png", type, nullptr, InputSpace::from_file, srgb);
        check(bits + "-linear.png", type, "linear", InputSpace::from_file, linear);
        check(bits + "-gamma.png", type, "GammaCorrected2.2", InputSpace::from_file,
              [](float v) { return std::pow(v, 2.2f); });
        check(bits + "-forced.tif", type, "linear", InputSpace::srgb, srgb);
    }
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

// A JPEG whose APP13 segment's IPTC block claims more bytes than the segment holds is refused,
// naming the file, before OpenImageIO 2.4 reads past the segment (kdop's image fuzzer found it
// under ASan); the same file with a block that fits reads as before.
TEST(ImageIo, AJpegsIptcBlockLongerThanItsSegmentIsRefused) {
    test::TempDir dir;
    const std::string jpeg = test::read_file(KDOP_SOURCE_DIR "/tests/fuzz/image_corpus/rgb8.jpg");
    ASSERT_EQ(jpeg.substr(0, 2), std::string("\xFF\xD8"));
    // An APP13 segment right after SOI: "Photoshop 3.0\0", "8BIM", resource 0x0404, 4 bytes of
    // padding, the block's 16-bit size, then `held` bytes of IIM records.
    auto with_app13 = [&](unsigned claimed, unsigned held) {
        std::string block = std::string("Photoshop 3.0") + '\0' + "8BIM" + "\x04\x04" + std::string(4, '\0');
        block += char(claimed >> 8);
        block += char(claimed & 0xFF);
        for (unsigned i = 0; i < held; ++i) block += i % 5 == 0 ? '\x1c' : '\x02';
        const std::size_t length = block.size() + 2;
        return jpeg.substr(0, 2) + "\xFF\xED" + char(length >> 8) + char(length & 0xFF) + block + jpeg.substr(2);
    };
    test::write_file(dir / "overrun.jpg", with_app13(0xFFFF, 10));
    auto refused = read_image((dir / "overrun.jpg").string());
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().message, (dir / "overrun.jpg").string() +
                                           ": cannot read image: its APP13 segment's IPTC block claims 65535 bytes, "
                                           "and the segment holds 10");
    auto size = read_image_size((dir / "overrun.jpg").string());
    ASSERT_FALSE(size);
    EXPECT_NE(size.error().message.find("claims 65535 bytes"), std::string::npos);
    // Cut inside the signature: the library's strcmp would read on.
    std::string cut = jpeg.substr(0, 2) + "\xFF\xED" + '\0' + '\x07' + "Photo";
    test::write_file(dir / "cut.jpg", cut);
    auto short_signature = read_image((dir / "cut.jpg").string());
    ASSERT_FALSE(short_signature);
    EXPECT_NE(short_signature.error().message.find("inside the \"Photoshop 3.0\" signature"), std::string::npos)
        << short_signature.error().message;

    test::write_file(dir / "whole.jpg", with_app13(10, 10));
    auto read = read_image((dir / "whole.jpg").string());
    ASSERT_TRUE(read) << read.error().message;
    auto plain = read_image(KDOP_SOURCE_DIR "/tests/fuzz/image_corpus/rgb8.jpg");
    ASSERT_TRUE(plain);
    EXPECT_EQ(read->pixels, plain->pixels);
}

TEST(ImageIo, LossyFormatsAreRefusedBeforeAnythingIsWritten) {
    test::TempDir dir;
    auto written = write_image((dir / "out.jpg").string(), noise(8, 1.0f));
    ASSERT_FALSE(written);
    EXPECT_NE(written.error().message.find("jpeg is lossy"), std::string::npos) << written.error().message;
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

// The 8-bit codes found by search are the formula's (linear_to_srgb, then OpenImageIO's conversion)
// for every float within 2^16 of each step, both sides, and for every 61st float of [0, 1]; each
// step is where the formula's code first reaches it.
TEST(SrgbBytes, TheSearchGivesTheFormulasCodes) {
    for (const auto& [steps, formula] :
         {std::pair{&ByteSteps::srgb(), &srgb_byte_by_formula}, std::pair{&ByteSteps::unit(), &unit_byte_by_formula}}) {
        std::size_t checked = 0;
        auto expect_same = [&](std::uint32_t bits) {
            const float v = std::bit_cast<float>(bits);
            ASSERT_EQ(steps->code(v), formula(v)) << "at " << v << " (bits " << bits << ")";
            ++checked;
        };
        const std::uint32_t one = std::bit_cast<std::uint32_t>(1.0f);
        for (int code = 1; code <= 255; ++code) {
            const std::uint32_t step = std::bit_cast<std::uint32_t>(steps->step(code));
            ASSERT_EQ(formula(steps->step(code)), code);
            ASSERT_LT(formula(std::bit_cast<float>(step - 1)), code);
            for (std::uint32_t b = step - std::min(step, 1u << 16); b <= std::min(one, step + (1u << 16)); ++b)
                expect_same(b);
        }
        for (std::uint32_t b = 0; b <= one; b += 61) expect_same(b);
        expect_same(one);
        EXPECT_GT(checked, 30'000'000u);
    }
    EXPECT_EQ(ByteSteps::srgb().code(0.0f), 0);
    EXPECT_EQ(ByteSteps::srgb().code(1.0f), 255);
    EXPECT_EQ(ByteSteps::srgb().code(0.5f), 188); // 0.5 linear is sRGB 0.735
}

} // namespace
} // namespace kdop
