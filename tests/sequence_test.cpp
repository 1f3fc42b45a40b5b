// The frame-sequence format (sequence/sequence.h): what a valid sequence reads as, the four
// motion conventions, and every kind of bad input refused with the file and the reason.
#include "sequence/sequence.h"

#include "images/image_io.h"
#include "sequence/frame_source.h"
#include "tests/test_support.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

namespace kdop {
namespace {
namespace fs = std::filesystem;

constexpr std::uint32_t kWidth = 8, kHeight = 4;

// Pixel (x, y) moved by (x - 3, 0.5 y) pixels since the previous frame: what the surface there was
// at, as the canonical convention states it (previous frame, pixels, y down).
glm::vec2 true_motion(std::uint32_t x, std::uint32_t y) { return {float(x) - 3.0f, 0.5f * float(y)}; }

struct SequenceDir {
    test::TempDir dir;
    fs::path operator/(const std::string& name) const { return dir / name; }

    // Writes frame files color/N.exr and motion/N.exr in `convention`, and returns their JSON entry.
    std::string frame(int n, const MotionConvention& convention = {}, std::string extra = "") const {
        fs::create_directories(dir / "color");
        fs::create_directories(dir / "motion");
        Image color(kWidth, kHeight, {0.1f * float(n), 0.5f, 2.0f, 1.0f}); // HDR is allowed
        EXPECT_TRUE(write_image((dir / fmt::format("color/{:04}.exr", n)).string(), color));
        Image motion(kWidth, kHeight);
        for (std::uint32_t y = 0; y < kHeight; ++y)
            for (std::uint32_t x = 0; x < kWidth; ++x) {
                glm::vec2 m = true_motion(x, y);
                if (convention.points_to == MotionConvention::PointsTo::current) m = -m;
                if (convention.y_axis == MotionConvention::YAxis::up) m.y = -m.y;
                if (convention.units == MotionConvention::Units::uv) m /= glm::vec2(kWidth, kHeight);
                motion.at(x, y) = {m.x, m.y, 0, 1};
            }
        EXPECT_TRUE(write_image((dir / fmt::format("motion/{:04}.exr", n)).string(), motion));
        return fmt::format(R"({{"color": "color/{0:04}.exr", "motion": "motion/{0:04}.exr"{1}}})", n, extra);
    }
    void json(const std::string& motion, const std::vector<std::string>& frames, int version = 1) const {
        std::string list;
        for (const std::string& f : frames) list += (list.empty() ? "" : ",\n  ") + f;
        test::write_file(dir / "sequence.json",
                         fmt::format("{{\"kdop_sequence\": {}, \"width\": {}, \"height\": {},\n \"motion\": {},\n "
                                     "\"frames\": [\n  {}]}}\n",
                                     version, kWidth, kHeight, motion, list));
    }
};

TEST(Sequence, ReadsTheListThenEachFrameWhenAsked) {
    SequenceDir s;
    const std::string first = s.frame(0), second = s.frame(1, {}, R"(, "jitter": [0.25, -0.5])");
    fs::create_directories(s / "reference");
    ASSERT_TRUE(write_image((s / "reference/0001.exr").string(), Image(kWidth, kHeight, {0.5f, 0.5f, 0.5f, 1})));
    const std::string third = s.frame(2, {}, R"(, "camera_cut": true, "reference": "reference/0001.exr")");
    s.json(R"({"units": "pixels", "points_to": "previous", "y_axis": "down"})", {first, second, third});

    auto sequence = read_sequence(s.dir.path());
    ASSERT_TRUE(sequence) << sequence.error().message;
    EXPECT_EQ(sequence->width, kWidth);
    EXPECT_EQ(sequence->frames.size(), 3u);
    EXPECT_FALSE(sequence->frames[0].jitter);
    EXPECT_EQ(*sequence->frames[1].jitter, glm::vec2(0.25f, -0.5f));
    EXPECT_TRUE(sequence->starts_history(0));
    EXPECT_FALSE(sequence->starts_history(1));
    EXPECT_TRUE(sequence->starts_history(2)) << "a camera cut drops the history";

    auto start = load_frame(*sequence, 0);
    ASSERT_TRUE(start) << start.error().message;
    EXPECT_TRUE(start->motion.empty()) << "no history to reproject on the first frame";
    auto frame = load_frame(*sequence, 1);
    ASSERT_TRUE(frame) << frame.error().message;
    EXPECT_EQ(frame->color.at(3, 2), glm::vec4(0.1f, 0.5f, 2.0f, 1.0f));
    ASSERT_EQ(frame->motion.size(), std::size_t(kWidth * kHeight));
    EXPECT_EQ(frame->motion[2 * kWidth + 7], true_motion(7, 2));
    EXPECT_FALSE(frame->reference);
    auto cut = load_frame(*sequence, 2);
    ASSERT_TRUE(cut && cut->reference);
    EXPECT_EQ(cut->reference->at(0, 0).r, 0.5f);
}

// Frames read for a resolve that does not read depth leave the depth files alone: neither decoded
// nor checked (a NaN in one is then no error); everything else is read as before.
TEST(Sequence, FramesReadWithoutDepthLeaveTheDepthFilesUnread) {
    SequenceDir s;
    fs::create_directories(s / "depth");
    ASSERT_TRUE(write_image((s / "depth/0000.exr").string(), Image(kWidth, kHeight, {0.5f, 0, 0, 1})));
    ASSERT_TRUE(write_image((s / "depth/0001.exr").string(), Image(kWidth, kHeight, {NAN, 0, 0, 1})));
    s.json(R"({"units": "pixels", "points_to": "previous", "y_axis": "down"})",
           {s.frame(0, {}, R"(, "depth": "depth/0000.exr")"), s.frame(1, {}, R"(, "depth": "depth/0001.exr")")});
    auto sequence = read_sequence(s.dir.path());
    ASSERT_TRUE(sequence) << sequence.error().message;
    const SequenceFrames frames(*sequence, InputSpace::from_file);
    EXPECT_TRUE(frames.has_depth());
    auto first = frames.frame(0);
    ASSERT_TRUE(first && first->depth) << "depth is read where it is asked for";
    auto refused = frames.frame(1);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("depth must be finite"), std::string::npos) << refused.error().message;

    const SequenceFrames without = frames.without_depth();
    EXPECT_FALSE(without.has_depth());
    auto start = without.frame(0), next = without.frame(1);
    ASSERT_TRUE(start) << start.error().message;
    ASSERT_TRUE(next) << next.error().message;
    EXPECT_FALSE(start->depth || next->depth);
    EXPECT_EQ(start->color.pixels, first->color.pixels);
    ASSERT_EQ(next->motion.size(), std::size_t(kWidth * kHeight));
    EXPECT_EQ(next->motion[2 * kWidth + 7], true_motion(7, 2));
}

// Unreal's and Unity's velocities point to the current frame; UV units divide by the frame's size;
// Blender's y points up. Each convention describing the same motion gives the same motion, bit for bit.
TEST(Sequence, EveryMotionConventionGivesTheSameMotion) {
    using U = MotionConvention::Units;
    using P = MotionConvention::PointsTo;
    using Y = MotionConvention::YAxis;
    const std::pair<MotionConvention, const char*> conventions[] = {
        {{U::pixels, P::previous, Y::down}, R"({"units": "pixels", "points_to": "previous", "y_axis": "down"})"},
        {{U::pixels, P::current, Y::down}, R"({"points_to": "current"})"},
        {{U::uv, P::previous, Y::down}, R"({"units": "uv"})"},
        {{U::pixels, P::previous, Y::up}, R"({"y_axis": "up"})"},
        {{U::uv, P::current, Y::up}, R"({"units": "uv", "points_to": "current", "y_axis": "up"})"},
    };
    for (const auto& [convention, text] : conventions) {
        SequenceDir s;
        s.json(text, {s.frame(0, convention), s.frame(1, convention)});
        auto sequence = read_sequence(s.dir.path());
        ASSERT_TRUE(sequence) << text << ": " << sequence.error().message;
        auto frame = load_frame(*sequence, 1);
        ASSERT_TRUE(frame) << text << ": " << frame.error().message;
        for (std::uint32_t y = 0; y < kHeight; ++y)
            for (std::uint32_t x = 0; x < kWidth; ++x)
                ASSERT_EQ(frame->motion[y * kWidth + x], true_motion(x, y)) << text << " at " << x << ", " << y;
    }
}

TEST(Sequence, ReadsTheDepthConvention) {
    SequenceDir s;
    s.json("{}", {s.frame(0)});
    auto plain = read_sequence(s.dir.path());
    ASSERT_TRUE(plain) << plain.error().message;
    EXPECT_FALSE(plain->depth_nearer_larger) << "smaller is nearer by default";
    s.json(R"({}, "depth": {"nearer": "larger"})", {s.frame(0)});
    auto reversed = read_sequence(s.dir.path());
    ASSERT_TRUE(reversed) << reversed.error().message;
    EXPECT_TRUE(reversed->depth_nearer_larger);
    for (const char* bad : {R"({"nearer": "closer"})", R"({"near": "larger"})", R"("larger")"}) {
        s.json(std::string(R"({}, "depth": )") + bad, {s.frame(0)});
        auto refused = read_sequence(s.dir.path());
        ASSERT_FALSE(refused) << bad;
        EXPECT_NE(refused.error().message.find("sequence.json: depth"), std::string::npos) << refused.error().message;
    }
}

// "color": {"range": ...} says what the frames are measured in; reading a frame checks no range.
TEST(Sequence, ReadsTheColorRange) {
    SequenceDir s;
    s.json("{}", {s.frame(0)});
    auto plain = read_sequence(s.dir.path());
    ASSERT_TRUE(plain) << plain.error().message;
    EXPECT_EQ(plain->color_range, ColorRange::ldr) << "ldr by default";
    auto frame = load_frame(*plain, 0);
    ASSERT_TRUE(frame) << frame.error().message;
    EXPECT_EQ(frame->color.at(0, 0).b, 2.0f) << "reading does not clamp";
    s.json(R"({}, "color": {"range": "hdr"})", {s.frame(0)});
    auto hdr = read_sequence(s.dir.path());
    ASSERT_TRUE(hdr) << hdr.error().message;
    EXPECT_EQ(hdr->color_range, ColorRange::hdr);
    for (const char* bad : {R"({"range": "high"})", R"({"ranges": "hdr"})", R"("hdr")"}) {
        s.json(std::string(R"({}, "color": )") + bad, {s.frame(0)});
        auto refused = read_sequence(s.dir.path());
        ASSERT_FALSE(refused) << bad;
        EXPECT_NE(refused.error().message.find("sequence.json: color"), std::string::npos) << refused.error().message;
    }
}

TEST(Sequence, BadInputIsRefusedNamingTheFileAndTheReason) {
    struct Case {
        std::string what, expected;
        std::function<void(SequenceDir&)> make;
    };
    auto plain = [](SequenceDir& s) { s.json("{}", {s.frame(0), s.frame(1)}); };
    const Case cases[] = {
        {"no sequence.json", "sequence.json: does not exist", [](SequenceDir&) {}},
        {"not JSON", "sequence.json:3:1: not JSON: syntax error while parsing object key",
         [](SequenceDir& s) { test::write_file(s / "sequence.json", "{\"kdop_sequence\": 1,\n\"width\": 8,\n}"); }},
        {"a number past a double's range", "sequence.json: not JSON kdop can read: ",
         [](SequenceDir& s) { test::write_file(s / "sequence.json", "99e9999"); }},
        {"a newer version", "kdop_sequence: version 2; this kdop reads version 1",
         [](SequenceDir& s) { s.json("{}", {s.frame(0)}, 2); }},
        {"an unknown convention",
         "motion.points_to: \"next\" is not a convention kdop knows; expected \"previous\" "
         "or \"current\"",
         [](SequenceDir& s) { s.json(R"({"points_to": "next"})", {s.frame(0)}); }},
        {"a misspelled key", "motion: unknown key \"point_to\"",
         [](SequenceDir& s) { s.json(R"({"point_to": "current"})", {s.frame(0)}); }},
        {"no frames", "frames: expected a list of at least one frame", [](SequenceDir& s) { s.json("{}", {}); }},
        {"a missing frame file", "frames[1].color: ",
         [](SequenceDir& s) {
             s.json("{}", {s.frame(0), s.frame(1)});
             fs::remove(s / "color/0001.exr");
         }},
        {"a missing file named with control bytes, shown escaped", R"(color/\x1b[31m\x7f.exr: does not exist)",
         [](SequenceDir& s) { s.json("{}", {R"({"color": "color/\u001b[31m\u007f.exr"})"}); }},
        {"a frame file outside the folder", "frames[0].color: \"../elsewhere.exr\" is outside the sequence's folder",
         [](SequenceDir& s) { s.json("{}", {R"({"color": "../elsewhere.exr"})"}); }},
        {"no motion where a history is", "frames[1]: has no \"motion\" file",
         [](SequenceDir& s) {
             s.frame(1);
             s.json("{}", {s.frame(0), R"({"color": "color/0001.exr"})"});
         }},
        {"a jitter past half a pixel", "frames[0].jitter: [0.7,0.0] is not [x, y] within half a pixel",
         [](SequenceDir& s) { s.json("{}", {s.frame(0, {}, R"(, "jitter": [0.7, 0.0])")}); }},
        {"a folder as a frame", "is a directory",
         [](SequenceDir& s) {
             fs::create_directories(s / "color/dir.exr");
             s.json("{}", {R"({"color": "color/dir.exr"})"});
         }},
    };
    for (const Case& c : cases) {
        SequenceDir s;
        c.make(s);
        auto sequence = read_sequence(s.dir.path());
        ASSERT_FALSE(sequence) << c.what;
        EXPECT_NE(sequence.error().message.find(c.expected), std::string::npos) << c.what << "\n"
                                                                                << sequence.error().message;
    }

    // What only the frame's pixels show, found when the frame is loaded.
    const Case frame_cases[] = {
        {"a frame of another size", "color/0001.exr: 4x4, but the sequence is 8x4",
         [&](SequenceDir& s) {
             plain(s);
             ASSERT_TRUE(write_image((s / "color/0001.exr").string(), Image(4, 4)));
         }},
        {"NaN motion", "motion/0001.exr: pixel (2, 1) holds nan in channel 0; motion must be finite",
         [&](SequenceDir& s) {
             plain(s);
             Image motion(kWidth, kHeight);
             motion.at(2, 1).r = NAN;
             ASSERT_TRUE(write_image((s / "motion/0001.exr").string(), motion));
         }},
        {"motion with one channel", "motion/0001.exr: has 1 channel(s); kdop needs 2 here",
         [&](SequenceDir& s) {
             plain(s);
             const std::string path = (s / "motion/0001.exr").string();
             auto out = OIIO::ImageOutput::create(path);
             const std::vector<float> zeros(kWidth * kHeight, 0.0f);
             ASSERT_TRUE(out->open(path, OIIO::ImageSpec(kWidth, kHeight, 1, OIIO::TypeDesc::FLOAT)) &&
                         out->write_image(OIIO::TypeDesc::FLOAT, zeros.data()) && out->close());
         }},
        {"an unreadable frame", "color/0001.exr: cannot read image",
         [&](SequenceDir& s) {
             plain(s);
             test::write_file(s / "color/0001.exr", "not an image");
         }},
    };
    for (const Case& c : frame_cases) {
        SequenceDir s;
        c.make(s);
        auto sequence = read_sequence(s.dir.path());
        ASSERT_TRUE(sequence) << c.what << ": " << sequence.error().message;
        auto frame = load_frame(*sequence, 1);
        ASSERT_FALSE(frame) << c.what;
        EXPECT_NE(frame.error().message.find(c.expected), std::string::npos) << c.what << "\n" << frame.error().message;
    }
}

} // namespace
} // namespace kdop
