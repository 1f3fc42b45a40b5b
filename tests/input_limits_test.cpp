// Inputs refused before the work, and for their real reason (issue 58, findings 10, 11 and 12): an
// image whose header claims more than memory holds, `ulimit -v` included, refused with the memory
// it needs and never as std::bad_alloc; a background far larger than the frame read for the corner
// the frame uses; a sequence's file where the run writes its outputs; a frame path the kernel
// cannot open; an output naming an input, a usage error. The huge images are solid black PNGs of
// about a megabyte, made in milliseconds (huge_png below).
#include "core/input_files.h"
#include "images/image_io.h"
#include "scenes/sprite_scene.h"
#include "sequence/sequence.h"
#include "tests/test_support.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace kdop {
namespace {
namespace fs = std::filesystem;

std::string kdop(const std::string& args) { return test::kdop_binary() + " " + args; }

// A shell line that runs `command` with at most 3 GiB of address space (`ulimit -v`): far less
// than the 16000x16000 images below need (7 GiB and more), far more than kdop needs otherwise.
std::string limited(const std::string& command) { return "ulimit -v 3145728 && " + command; }

// AddressSanitizer reserves terabytes of address space for its shadow memory, so a sanitized kdop
// cannot start under any `ulimit -v`.
#if defined(__SANITIZE_ADDRESS__)
#define SKIP_UNDER_ULIMIT() GTEST_SKIP() << "AddressSanitizer's shadow memory does not fit under ulimit -v"
#else
#define SKIP_UNDER_ULIMIT() (void)0
#endif

void put_be32(std::string& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out += char((v >> shift) & 0xff);
}

// `count` zero bytes, raw-deflated and ended with a full flush: blocks that refer to nothing before
// them and end on a byte, so any number of copies, one after another, inflate to that many runs of
// zeros.
std::string deflated_zeros(std::size_t count) {
    z_stream z{};
    EXPECT_EQ(deflateInit2(&z, 9, Z_DEFLATED, -15, 9, Z_DEFAULT_STRATEGY), Z_OK);
    std::vector<unsigned char> in(count), out(deflateBound(&z, count) + 64);
    z.next_in = in.data();
    z.avail_in = unsigned(count);
    z.next_out = out.data();
    z.avail_out = unsigned(out.size());
    EXPECT_EQ(deflate(&z, Z_FULL_FLUSH), Z_OK);
    std::string bytes(reinterpret_cast<const char*>(out.data()), out.size() - z.avail_out);
    deflateEnd(&z);
    return bytes;
}

// A solid black RGB PNG of width x height, 8 bits, interlaced (Adam7) or not: its image data is
// all zeros (each row's filter byte too), deflated as one compressed megabyte of zeros repeated,
// so a 16000x16000 file is 0.7 MB and takes milliseconds to make, where zlib would deflate 768 MB.
void huge_png(const fs::path& path, std::uint32_t width, std::uint32_t height, bool interlaced = false) {
    auto rows = [](std::uint64_t w, std::uint64_t h) { return w && h ? h * (1 + 3 * w) : 0; };
    std::uint64_t raw = 0;
    if (!interlaced) {
        raw = rows(width, height);
    } else {
        // Adam7's passes: first column and row, and the steps between them.
        constexpr std::array<std::array<std::uint32_t, 4>, 7> passes{
            {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4}, {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}}};
        for (const auto& [x0, y0, dx, dy] : passes)
            raw += rows(width > x0 ? (width - x0 + dx - 1) / dx : 0, height > y0 ? (height - y0 + dy - 1) / dy : 0);
    }
    constexpr std::size_t kBlock = 1 << 20;
    const std::string block = deflated_zeros(kBlock);
    std::string zlib_stream = "\x78\x9c"; // deflate, 32 KiB window
    for (std::uint64_t i = 0; i < raw / kBlock; ++i) zlib_stream += block;
    zlib_stream += deflated_zeros(raw % kBlock);
    zlib_stream += std::string("\x01\x00\x00\xff\xff", 5);       // the last block: stored, empty
    put_be32(zlib_stream, std::uint32_t(raw % 65521) << 16 | 1); // Adler-32 of zeros: 1, and the count

    std::string png = "\x89PNG\r\n\x1a\n";
    auto chunk = [&](const char* type, const std::string& data) {
        put_be32(png, std::uint32_t(data.size()));
        const std::string body = type + data;
        png += body;
        put_be32(png, std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
    };
    std::string header;
    put_be32(header, width);
    put_be32(header, height);
    header += std::string{8, 2, 0, 0, char(interlaced ? 1 : 0)}; // 8 bits, RGB, deflate, filters, interlace
    chunk("IHDR", header);
    chunk("IDAT", zlib_stream);
    chunk("IEND", "");
    test::write_file(path, png);
}

// ---------------------------------------------------------------------------------------------
// Images

TEST(InputLimits, TheHugeImagesAreWhatTheyClaim) {
    test::TempDir dir;
    for (bool interlaced : {false, true}) {
        const fs::path path = dir / (interlaced ? "interlaced.png" : "plain.png");
        huge_png(path, 37, 23, interlaced);
        auto image = read_image(path.string());
        ASSERT_TRUE(image) << image.error().message;
        EXPECT_EQ(image->width, 37u);
        EXPECT_EQ(image->height, 23u);
        for (const glm::vec4& p : image->pixels) EXPECT_EQ(p, glm::vec4(0, 0, 0, 1));
    }
    huge_png(dir / "huge.png", 16000, 16000);
    EXPECT_LT(fs::file_size(dir / "huge.png"), 1u << 20);
    auto size = read_image_size((dir / "huge.png").string());
    ASSERT_TRUE(size);
    EXPECT_EQ(*size, glm::uvec2(16000, 16000));
}

// A corner is the whole read's corner bit for bit, from formats read by rows (8- and 16-bit PNG,
// EXR) and from those read whole and cropped (TGA, an interlaced PNG); a corner larger than the
// image is the image.
TEST(InputLimits, ACornerIsTheWholeReadsCorner) {
    test::TempDir dir;
    Image picture(40, 30);
    for (std::uint32_t y = 0; y < 30; ++y)
        for (std::uint32_t x = 0; x < 40; ++x)
            picture.at(x, y) = {float(x) / 40, float(y) / 30, float((x * 7 + y * 3) % 11) / 11,
                                0.25f + float(x % 3) / 4};
    std::vector<fs::path> files;
    for (const char* name : {"rgba8.png", "float.exr", "rgba.tga"}) {
        files.push_back(dir / name);
        ASSERT_TRUE(write_image(files.back().string(), picture)) << name;
    }
    files.push_back(dir / "rgb16.png");
    {
        auto out = OIIO::ImageOutput::create(files.back().string());
        OIIO::ImageSpec spec(40, 30, 3, OIIO::TypeDesc::UINT16);
        std::vector<std::uint16_t> values(40 * 30 * 3);
        for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::uint16_t(i * 977);
        ASSERT_TRUE(out->open(files.back().string(), spec) && out->write_image(OIIO::TypeDesc::UINT16, values.data()) &&
                    out->close());
    }
    files.push_back(dir / "interlaced.png");
    huge_png(files.back(), 40, 30, true);
    for (const fs::path& file : files) {
        auto whole = read_image(file.string());
        ASSERT_TRUE(whole) << whole.error().message;
        for (const glm::uvec2 corner : {glm::uvec2(17, 9), glm::uvec2(40, 1), glm::uvec2(1, 30), glm::uvec2(64, 64)}) {
            auto part = read_image_corner(file.string(), corner.x, corner.y);
            ASSERT_TRUE(part) << part.error().message;
            ASSERT_EQ(part->width, std::min(corner.x, 40u)) << file;
            ASSERT_EQ(part->height, std::min(corner.y, 30u)) << file;
            for (std::uint32_t y = 0; y < part->height; ++y)
                for (std::uint32_t x = 0; x < part->width; ++x)
                    ASSERT_EQ(std::memcmp(&part->at(x, y), &whole->at(x, y), sizeof(glm::vec4)), 0)
                        << file << " at (" << x << ", " << y << ")";
        }
    }
}

// The background is tiled from its corner: a 16000x16000 PNG gives the frame the same pixels as a
// 64x36 crop of it, and costs what the crop costs (the whole would need 7 GiB).
TEST(InputLimits, ABackgroundIsReadForTheCornerTheFrameUses) {
    test::TempDir dir;
    huge_png(dir / "huge.png", 16000, 16000);
    auto scene = read_sprite_scene((dir / "huge.png").string(), 64, 36);
    ASSERT_TRUE(scene) << scene.error().message;
    EXPECT_EQ(scene->background().width, 64u);
    EXPECT_EQ(scene->background().height, 36u);
    EXPECT_EQ(scene->background().pixels.front(), glm::vec4(0, 0, 0, 1));
}

TEST(InputLimits, AHugeImageIsRefusedUpFrontUnderUlimitNamingTheMemory) {
    SKIP_UNDER_ULIMIT();
    test::TempDir dir;
    huge_png(dir / "huge.png", 16000, 16000);
    const std::string huge = (dir / "huge.png").string(), map = (dir / "map.png").string();
    auto flip = test::run(limited(kdop("flip --cpu --reference " + huge + " --test " + huge + " --out " + map)));
    EXPECT_EQ(flip.exit_code, 1) << flip.err;
    EXPECT_NE(flip.err.find(huge + ": a 16000x16000 image: needs about 6.7 GiB of memory, "), std::string::npos)
        << flip.err;
    EXPECT_EQ(flip.err.find("bad_alloc"), std::string::npos) << flip.err;
    EXPECT_FALSE(fs::exists(map));
}

// kdop scene reads a background's corner alone, so a huge one fits where its whole would not;
// one that must be read whole (interlaced) is refused with the memory and what would fit.
TEST(InputLimits, AHugeBackgroundCostsItsCornerUnderUlimit) {
    SKIP_UNDER_ULIMIT();
    test::TempDir dir;
    huge_png(dir / "huge.png", 16000, 16000);
    auto scene = test::run(limited(kdop("scene --background " + (dir / "huge.png").string() +
                                        " --size 64x36 --frames 2 --animate on --out " + (dir / "seq").string())));
    ASSERT_EQ(scene.exit_code, 0) << scene.err;
    auto frame = read_image_size((dir / "seq" / "huge" / "color" / "0001.exr").string());
    ASSERT_TRUE(frame);
    EXPECT_EQ(*frame, glm::uvec2(64, 36));

    huge_png(dir / "interlaced.png", 16000, 16000, true);
    auto refused = test::run(limited(kdop("scene --background " + (dir / "interlaced.png").string() +
                                          " --size 64x36 --frames 2 --animate on --out " + (dir / "out").string())));
    EXPECT_EQ(refused.exit_code, 1) << refused.err;
    EXPECT_NE(
        refused.err.find("--background: " + (dir / "interlaced.png").string() + ": a 16000x16000 image: needs about"),
        std::string::npos)
        << refused.err;
    EXPECT_NE(refused.err.find("only its top-left 64x36 pixels are used, which a PNG without interlacing"),
              std::string::npos)
        << refused.err;
    EXPECT_FALSE(fs::exists(dir / "out" / "interlaced"));
}

// ---------------------------------------------------------------------------------------------
// Sequences

// A 4x4 sequence of two frames in `dir`: color/0000.exr and color/0001.exr, motion/0001.exr.
void small_sequence(const fs::path& dir, const std::string& second_color = "color/0001.exr") {
    fs::create_directories(dir / "color");
    fs::create_directories(dir / "motion");
    for (int i = 0; i < 2; ++i)
        EXPECT_TRUE(write_image((dir / fmt::format("color/{:04}.exr", i)).string(),
                                Image(4, 4, {0.25f * float(i + 1), 0.5f, 0.125f, 1})));
    EXPECT_TRUE(write_image((dir / "motion" / "0001.exr").string(), Image(4, 4, {0, 0, 0, 1})));
    test::write_file(dir / "sequence.json", fmt::format(R"({{"kdop_sequence": 1, "width": 4, "height": 4, "frames": [
  {{"color": "color/0000.exr"}}, {{"color": "{}", "motion": "motion/0001.exr"}}]}})",
                                                        second_color));
}

TEST(InputLimits, AFramePathTheKernelCannotOpenIsSaidSo) {
    test::TempDir dir;
    std::string deep = "color/";
    while (deep.size() < 4200) deep += "a/";
    small_sequence(dir / "deep", deep + "0001.exr");
    auto too_long = read_sequence(dir / "deep");
    ASSERT_FALSE(too_long);
    const std::string json = (dir / "deep" / "sequence.json").string();
    EXPECT_EQ(too_long.error().message.rfind(json + ": frames[1].color: \"color/a/a/", 0), 0u)
        << too_long.error().message;
    EXPECT_NE(too_long.error().message.find("Linux opens no path of 4096 bytes or more (PATH_MAX)"), std::string::npos)
        << too_long.error().message;
    EXPECT_EQ(too_long.error().message.find("outside"), std::string::npos) << too_long.error().message;

    small_sequence(dir / "wide", "color/" + std::string(300, 'b') + ".exr");
    auto wide = read_sequence(dir / "wide");
    ASSERT_FALSE(wide);
    EXPECT_NE(wide.error().message.find("frames[1].color: \"color/bbb"), std::string::npos) << wide.error().message;
    EXPECT_NE(wide.error().message.find("holds a name of 304 bytes; a file's name has at most 255 (NAME_MAX)"),
              std::string::npos)
        << wide.error().message;
}

// A frame whose header claims another size is refused from its header: under ulimit, the size,
// not the memory a 16000x16000 frame would need (which was the message when it was decoded first).
TEST(InputLimits, AFrameOfAnotherSizeIsRefusedFromItsHeader) {
    SKIP_UNDER_ULIMIT();
    test::TempDir dir;
    small_sequence(dir / "s", "color/huge.png");
    huge_png(dir / "s" / "color" / "huge.png", 16000, 16000);
    auto fit = test::run(limited(kdop("optimize --sequence " + (dir / "s").string() +
                                      " --axes 4 --starts 1 --iterations 2 --accuracy-samples 0 --out " +
                                      (dir / "fitted.axes").string())));
    EXPECT_EQ(fit.exit_code, 1) << fit.err;
    EXPECT_NE(fit.err.find((dir / "s" / "color" / "huge.png").string() + ": 16000x16000, but the sequence is 4x4"),
              std::string::npos)
        << fit.err;
    EXPECT_FALSE(fs::exists(dir / "fitted.axes"));
}

TEST(InputLimits, ASequenceFileInsideTheOutputFolderIsRefused) {
    test::TempDir dir;
    small_sequence(dir / "s");
    auto sequence = read_sequence(dir / "s");
    ASSERT_TRUE(sequence) << sequence.error().message;
    EXPECT_TRUE(check_outside(*sequence, dir / "out", "--out"));
    EXPECT_TRUE(check_outside(*sequence, dir / "s" / "report", "--out")) << "a folder of its own inside the sequence";
    auto inside = check_outside(*sequence, dir / "s", "--out");
    ASSERT_FALSE(inside);
    EXPECT_TRUE(inside.error().usage);
    EXPECT_EQ(inside.error().message, fmt::format("--out {0}/s: holds {0}/s/sequence.json, a file of the sequence "
                                                  "{0}/s; kdop writes this run's outputs there and never over an "
                                                  "input, so give a folder outside the sequence's files",
                                                  dir.path().string()));
    // A frame linked to a file in the output folder, inside the sequence's.
    fs::create_directories(dir / "s" / "out");
    fs::rename(dir / "s" / "color" / "0001.exr", dir / "s" / "out" / "0001.exr");
    fs::create_symlink("../out/0001.exr", dir / "s" / "color" / "0001.exr");
    auto linked = check_outside(*sequence, dir / "s" / "out", "--out");
    ASSERT_FALSE(linked);
    EXPECT_NE(linked.error().message.find("holds " + (dir / "s" / "color" / "0001.exr").string()), std::string::npos)
        << linked.error().message;
}

// What a frame read through its descriptor is noted as: its own path, which a refusal names.
TEST(InputLimits, AFrameIsNotedAsAnInputByItsOwnPath) {
    test::TempDir dir;
    small_sequence(dir / "s");
    protect_inputs(true);
    auto sequence = read_sequence(dir / "s");
    ASSERT_TRUE(sequence);
    // Noted on reading the list, before any frame is read: a depth file the resolve never reads too.
    EXPECT_EQ(noted_input_at(dir / "s" / "motion" / "0001.exr"), sequence->frames[1].motion);
    protect_inputs(false);
    protect_inputs(true);
    ASSERT_TRUE(load_frame(*sequence, 1));
    EXPECT_EQ(noted_input_at(dir / "s" / "color" / "0001.exr"), sequence->frames[1].color);
    protect_inputs(false);
}

// A file of the sequence that no fit reads (depth) is an input all the same: kdop optimize --out
// naming it wrote an axis set over it.
TEST(InputLimits, AnOutputNamingAnUnreadSequenceFileIsRefused) {
    test::TempDir dir;
    small_sequence(dir / "s");
    fs::create_directories(dir / "s" / "depth");
    ASSERT_TRUE(write_image((dir / "s" / "depth" / "0001.exr").string(), Image(4, 4, {0.5f, 0, 0, 1})));
    std::string json = test::read_file(dir / "s" / "sequence.json");
    json.replace(json.find("\"motion\": \"motion/0001.exr\""), 0, "\"depth\": \"depth/0001.exr\", ");
    test::write_file(dir / "s" / "sequence.json", json);
    const fs::path depth = dir / "s" / "depth" / "0001.exr";
    const std::string before = test::read_file(depth);
    auto fit = test::run(kdop("optimize --sequence " + (dir / "s").string() +
                              " --axes 4 --starts 1 --iterations 2 --accuracy-samples 0 --name fitted --out " +
                              depth.string()));
    EXPECT_NE(fit.exit_code, 0) << fit.err;
    EXPECT_NE(fit.err.find("--out " + depth.string() + ": is an input of this run"), std::string::npos) << fit.err;
    EXPECT_EQ(test::read_file(depth), before);
}

// ---------------------------------------------------------------------------------------------
// Outputs naming inputs

TEST(InputLimits, AFlipOutputNamingAnInputIsAUsageError) {
    test::TempDir dir;
    const std::string a = (dir / "a.png").string(), b = (dir / "b.png").string();
    ASSERT_TRUE(write_image(a, Image(8, 8, {0.5f, 0.5f, 0.5f, 1})));
    ASSERT_TRUE(write_image(b, Image(8, 8, {0.25f, 0.5f, 0.5f, 1})));
    const std::string before = test::read_file(b);
    for (const char* option : {"--out", "--csv", "--histogram"}) {
        auto r = test::run(kdop(fmt::format("flip --cpu --reference {} --test {} {} {}", a, b, option, b)));
        EXPECT_EQ(r.exit_code, 2) << option << ": " << r.err;
        EXPECT_NE(r.err.find(fmt::format("{} {}: is an input of this run", option, b)), std::string::npos) << r.err;
    }
    EXPECT_EQ(test::read_file(b), before);
}

// ---------------------------------------------------------------------------------------------
// On the device

TEST(CliInputLimits, EveryImageReadIsCheckedUnderUlimit) {
    SKIP_UNDER_ULIMIT();
    test::TempDir dir;
    huge_png(dir / "huge.png", 16000, 16000);
    const std::string huge = (dir / "huge.png").string();
    auto taa = test::run(limited(kdop("taa --background " + huge +
                                      " --size 64x36 --warmup 2 --frames 2 --sets aabb --modes clip --timing-rounds 1 "
                                      "--no-charts --viewer-frames 0 --out " +
                                      (dir / "taa").string())));
    EXPECT_EQ(taa.exit_code, 0) << "the background's corner alone is read: " << taa.err;
    for (const std::string& command :
         {"run --variant aabb-clip-n9 --current " + huge + " --history " + huge + " --out " + (dir / "r.exr").string(),
          "accuracy --sets aabb --images " + huge + " --out " + (dir / "accuracy").string()}) {
        auto r = test::run(limited(kdop(command)));
        EXPECT_EQ(r.exit_code, 1) << command << ": " << r.err;
        EXPECT_NE(r.err.find(huge + ": a 16000x16000 image: needs about"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("bad_alloc"), std::string::npos) << r.err;
    }
    EXPECT_FALSE(fs::exists(dir / "r.exr"));
    EXPECT_FALSE(fs::exists(dir / "accuracy"));
}

// A sequence whose files lie where kdop taa writes is refused before the work, as a usage error
// (here its second frame is where the run writes its ghosting picture's aliased frame, which was
// refused only after the work, named /proc/self/fd/3); a frame hard-linked to an output is found
// when the set is written, and named by its own path.
TEST(CliInputLimits, ASequenceFileWhereTheRunWritesIsRefused) {
    test::TempDir dir;
    small_sequence(dir / "s", "frames/s/aliased.exr");
    fs::create_directories(dir / "s" / "frames" / "s");
    fs::rename(dir / "s" / "color" / "0001.exr", dir / "s" / "frames" / "s" / "aliased.exr");
    const std::string taa = " --warmup 1 --sets aabb --modes clip --timing-rounds 1 --no-charts --viewer-frames 0 ";
    auto inside = test::run(kdop("taa --sequence " + (dir / "s").string() + taa + "--out " + (dir / "s").string()));
    EXPECT_EQ(inside.exit_code, 2) << inside.err;
    EXPECT_NE(inside.err.find("--out " + (dir / "s").string() + ": holds "), std::string::npos) << inside.err;
    EXPECT_EQ(inside.err.find("TAA of"), std::string::npos) << "refused before the work: " << inside.err;
    EXPECT_FALSE(fs::exists(dir / "s" / "taa.csv"));

    fs::create_directories(dir / "out" / "frames" / "s");
    fs::create_hard_link(dir / "s" / "color" / "0000.exr", dir / "out" / "frames" / "s" / "aliased.exr");
    auto linked = test::run(kdop("taa --sequence " + (dir / "s").string() + taa + "--out " + (dir / "out").string()));
    EXPECT_EQ(linked.exit_code, 1) << linked.err;
    EXPECT_NE(linked.err.find("(the same file as " + (dir / "s" / "color" / "0000.exr").string() + ")"),
              std::string::npos)
        << linked.err;
    EXPECT_EQ(linked.err.find("/proc/self/fd"), std::string::npos) << linked.err;
    EXPECT_FALSE(fs::exists(dir / "out" / "taa.csv"));
}

TEST(CliInputLimits, ARunOutputNamingAnInputIsAUsageError) {
    test::TempDir dir;
    const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
    ASSERT_TRUE(write_image(a, Image(8, 8, {0.5f, 0.5f, 0.5f, 1})));
    ASSERT_TRUE(write_image(b, Image(8, 8, {0.25f, 0.5f, 0.5f, 1})));
    auto r = test::run(kdop("run --variant aabb-clip-n9 --current " + a + " --history " + b + " --out " + b));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("--out " + b + ": is an input of this run"), std::string::npos) << r.err;
}

} // namespace
} // namespace kdop
