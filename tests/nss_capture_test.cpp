// Arm's NSS dataset capture layout (sequence/nss_capture.h): a small capture written by a Python
// script here, by hand (uncompressed scanline OpenEXR through struct, as Arm's captures are laid
// out: half RGBA color, motion and ground truth, float RGBA depth; NNNN.json), not by kdop; read
// back in kdop's conventions, and every malformed capture refused naming the file and the field.
#include "sequence/nss_capture.h"

#include "tests/test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace kdop {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

// The writer: argv[1] is a JSON object: root, sequence, ratio_folder, target [W, H], input [w, h],
// frames, jitter (a list of [x, y] in input pixels, cycled), cuts (frames with CameraCut),
// reverse_z, exposure ({"frame": multiplier}). A bright dot at input pixel (3 + f, 1 + f) in frame
// f moves one pixel right and one down a frame; its motion is written in NSS's convention.
constexpr const char* kWriter =
    R"py(# Writes a small NSS capture (Arm's layout) by hand: uncompressed scanline OpenEXR through struct.
import json, struct, sys, os

def exr(path, w, h, channels):
    # channels: {name: (pixel_type, values row-major)}; pixel_type 1 = HALF, 2 = FLOAT.
    names = sorted(channels)
    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data
    chlist = b"".join(n.encode() + b"\0" + struct.pack("<iB3xii", channels[n][0], 0, 1, 1) for n in names) + b"\0"
    box = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    header = (attr("channels", "chlist", chlist) + attr("compression", "compression", b"\0") +
              attr("dataWindow", "box2i", box) + attr("displayWindow", "box2i", box) +
              attr("lineOrder", "lineOrder", b"\0") + attr("pixelAspectRatio", "float", struct.pack("<f", 1.0)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    lines = []
    for y in range(h):
        data = b""
        for n in names:
            kind, values = channels[n]
            row = values[y * w:(y + 1) * w]
            data += struct.pack("<%d%s" % (w, "e" if kind == 1 else "f"), *row)
        lines.append(struct.pack("<ii", y, len(data)) + data)
    start = 8 + len(header) + 8 * h
    offsets, at = [], start
    for line in lines:
        offsets.append(at)
        at += len(line)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(struct.pack("<ii", 20000630, 2) + header + struct.pack("<%dQ" % h, *offsets) + b"".join(lines))

def rgba(w, h, pixel, kind=1):
    values = [pixel(x, y) for y in range(h) for x in range(w)]
    return {c: (kind, [v[i] for v in values]) for i, c in enumerate("RGBA")}

spec = json.loads(sys.argv[1])
root, seq, ratio = spec["root"], spec["sequence"], spec["ratio_folder"]
W, H, w, h, n = spec["target"][0], spec["target"][1], spec["input"][0], spec["input"][1], spec["frames"]
dot = lambda f: (3 + f, 1 + f)  # the bright dot's input pixel in frame f: one pixel right and down a frame
frames = []
for f in range(n):
    dx, dy = dot(f)
    exr(f"{root}/{ratio}/color/{seq}/{f:04}.exr", w, h,
        rgba(w, h, lambda x, y: (4.0, 4.0, 4.0, 1.0) if (x, y) == (dx, dy) else (0.125, 0.25, 0.5, 1.0)))
    # NSS motion: uv now minus uv in the previous frame, in units of this file's size, v down.
    exr(f"{root}/{ratio}/motion/{seq}/{f:04}.exr", w, h,
        rgba(w, h, lambda x, y: (1.0 / w, 1.0 / h, 0.0, 1.0) if (x, y) == (dx, dy) and f > 0 else (0.0, 0.0, 0.0, 1.0)))
    exr(f"{root}/{ratio}/depth/{seq}/{f:04}.exr", w, h, rgba(w, h, lambda x, y: (0.25, 0.0, 0.0, 1.0), kind=2))
    exr(f"{root}/ground_truth/{seq}/{f:04}.exr", W, H,
        rgba(W, H, lambda x, y: (4.0, 4.0, 4.0, 1.0) if (x // 2, y // 2) == (dx, dy) else (0.125, 0.25, 0.5, 1.0)))
    jitter = spec["jitter"][f % len(spec["jitter"])]
    entry = {"Frame": f, "FovX": 1.07, "FovY": 0.64, "CameraNearPlane": 10, "CameraFarPlane": -1,
             "ViewProjection": [0.0] * 16, "Jitter": {"X": jitter[0], "Y": jitter[1]},
             # Index 0 (x1_5) holds a decoy: x2's jitter is at UpscalingRatiosIndices' x2_index, 1.
             "NormalizedPerRatioJitter": [{"X": 0.01, "Y": 0.01}, {"X": jitter[0] / w, "Y": jitter[1] / h},
                                          {"X": 0, "Y": 0}, {"X": 0, "Y": 0}],
             "Exposure": spec.get("exposure", {}).get(str(f), 1.0)}
    if f in spec.get("cuts", []):
        entry["CameraCut"] = True
    frames.append(entry)
meta = {"Version": "1.0.1", "EmulatedFramerate": 30, "TargetResolution": {"X": W, "Y": H},
        "Samples": {"Sequence": "TiledHalton", "Count": 16, "Quantized": True}, "ReverseZ": spec.get("reverse_z", False),
        "UpscalingRatiosIndices": {"x1_5_index": 0, "x2_index": 1, "x1_7_index": 2, "x1_3_index": 3},
        "OpaqueOnlyColor_Exported": False, "GTColorSpace": "Linear", "Frames": frames}
with open(f"{root}/{seq}.json", "w") as out:
    json.dump(meta, out, indent="\t")
)py";

struct Capture {
    test::TempDir dir;
    fs::path root() const { return dir / "capture"; }
    fs::path json_file() const { return root() / "0000.json"; }
};

json default_spec() {
    return {{"sequence", "0000"},    {"ratio_folder", "x2"}, {"target", {32, 18}},
            {"input", {16, 9}},      {"frames", 6},          {"jitter", {{0.25, -0.125}}},
            {"cuts", json::array()}, {"reverse_z", false},   {"exposure", json::object()}};
}

// Writes the capture `spec` describes under a fresh folder, through the Python writer.
void write_capture(const Capture& c, json spec) {
    spec["root"] = c.root().string();
    const fs::path script = c.dir / "write_nss.py";
    test::write_file(script, kWriter);
    auto ran = test::run({KDOP_PYTHON, script.string(), spec.dump()});
    ASSERT_EQ(ran.exit_code, 0) << ran.err;
}

json read_json(const fs::path& file) { return json::parse(test::read_file(file)); }
void write_json(const fs::path& file, const json& value) { test::write_file(file, value.dump(1, '\t')); }

TEST(NssCapture, ReadsSizesJitterCutsAndExposure) {
    Capture c;
    json spec = default_spec();
    spec["cuts"] = {3};
    spec["exposure"] = {{"1", 2.0}};
    write_capture(c, spec);
    auto capture = read_nss_capture(c.root(), "0000", 2.0);
    ASSERT_TRUE(capture) << capture.error().message;
    const NssFrames frames(*capture);
    EXPECT_EQ(frames.name(), "0000");
    EXPECT_EQ(frames.width(), 32u);
    EXPECT_EQ(frames.height(), 18u);
    EXPECT_EQ(frames.input_width(), 16u);
    EXPECT_EQ(frames.input_height(), 9u);
    EXPECT_TRUE(frames.upscales());
    EXPECT_EQ(frames.frame_count(), 6u);
    EXPECT_EQ(frames.color_range(), ColorRange::hdr);
    EXPECT_TRUE(frames.has_reference());
    EXPECT_TRUE(frames.reads_ahead());
    // NormalizedPerRatioJitter[x2_index = 1] = (0.25 / 16, -0.125 / 9), in input pixels with no
    // change of sign; index 0 holds a decoy.
    for (std::size_t i = 0; i < 6; ++i) {
        ASSERT_TRUE(frames.jitter(i));
        EXPECT_NEAR(frames.jitter(i)->x, 0.25f, 1e-6f);
        EXPECT_NEAR(frames.jitter(i)->y, -0.125f, 1e-6f);
    }
    // CameraCut at frame 3 starts a history, as the first frame does.
    for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(frames.starts_history(i), i == 0 || i == 3) << i;
    auto cut = frames.frame(3);
    ASSERT_TRUE(cut) << cut.error().message;
    EXPECT_TRUE(cut->motion.empty());
    EXPECT_FLOAT_EQ(cut->jitter.x, frames.jitter(3)->x);

    auto first = frames.frame(0);
    ASSERT_TRUE(first) << first.error().message;
    EXPECT_EQ(first->color.width, 16u);
    EXPECT_EQ(first->color.height, 9u);
    ASSERT_TRUE(first->reference);
    EXPECT_EQ(first->reference->width, 32u);
    EXPECT_EQ(first->reference->height, 18u);
    EXPECT_FLOAT_EQ(first->color.at(0, 0).x, 0.125f);
    EXPECT_FLOAT_EQ(first->color.at(0, 0).w, 1.0f);
    EXPECT_FLOAT_EQ(first->color.at(3, 1).x, 4.0f);      // the dot
    EXPECT_FLOAT_EQ(first->reference->at(7, 3).y, 4.0f); // the dot, 2x2 in the reference
    // Exposure 2 on frame 1 multiplies its color and its reference alike.
    auto exposed = frames.frame(1);
    ASSERT_TRUE(exposed) << exposed.error().message;
    EXPECT_FLOAT_EQ(exposed->color.at(0, 0).z, 1.0f);
    EXPECT_FLOAT_EQ(exposed->color.at(4, 2).x, 8.0f);
    EXPECT_FLOAT_EQ(exposed->reference->at(0, 0).y, 0.5f);
    EXPECT_FLOAT_EQ(exposed->color.at(0, 0).w, 1.0f);
}

// The tracked feature: the dot at input pixel (3 + f, 1 + f). After reading, the motion at the
// dot's pixel points to where the dot was in the previous frame, in input pixels: (-1, -1).
TEST(NssCapture, MotionAtATrackedDotPointsToWhereItWas) {
    Capture c;
    write_capture(c, default_spec());
    auto capture = read_nss_capture(c.root(), "0000", 2.0);
    ASSERT_TRUE(capture) << capture.error().message;
    const NssFrames frames(*capture);
    for (std::size_t f = 1; f < 6; ++f) {
        auto frame = frames.frame(f);
        ASSERT_TRUE(frame) << frame.error().message;
        ASSERT_EQ(frame->motion.size(), 16u * 9u);
        const std::uint32_t x = 3 + std::uint32_t(f), y = 1 + std::uint32_t(f);
        ASSERT_FLOAT_EQ(frame->color.at(x, y).x, 4.0f); // the dot is there
        const glm::vec2 m = frame->motion[y * 16 + x];
        const glm::vec2 previous = glm::vec2(x, y) + m;
        EXPECT_NEAR(previous.x, float(x - 1), 2e-3f) << "frame " << f;
        EXPECT_NEAR(previous.y, float(y - 1), 2e-3f) << "frame " << f;
        // ... which is where the previous frame's dot is.
        auto before = frames.frame(f - 1);
        ASSERT_TRUE(before) << before.error().message;
        EXPECT_FLOAT_EQ(
            before->color.at(std::uint32_t(std::lround(previous.x)), std::uint32_t(std::lround(previous.y))).x, 4.0f);
        EXPECT_EQ(frame->motion[0], glm::vec2(0.0f)); // the still background
    }
}

TEST(NssCapture, ReverseZBecomesForwardDepth) {
    for (bool reverse : {false, true}) {
        Capture c;
        json spec = default_spec();
        spec["reverse_z"] = reverse;
        write_capture(c, spec);
        auto capture = read_nss_capture(c.root(), "0000", 2.0);
        ASSERT_TRUE(capture) << capture.error().message;
        EXPECT_EQ(capture->reverse_z, reverse);
        const NssFrames frames(*capture);
        EXPECT_TRUE(frames.has_depth());
        auto frame = frames.frame(1);
        ASSERT_TRUE(frame) << frame.error().message;
        ASSERT_TRUE(frame->depth);
        // Stored 0.25: forward as it is, reversed 1 - 0.25 (Arm's reader does the same).
        EXPECT_FLOAT_EQ(frame->depth->at(2, 2).x, reverse ? 0.75f : 0.25f);
        auto without = frames.without_depth().frame(1);
        ASSERT_TRUE(without) << without.error().message;
        EXPECT_FALSE(without->depth);
        EXPECT_FALSE(frames.without_depth().has_depth());
    }
}

TEST(NssCapture, RatioFoldersAreNamedAsArmsReaderNamesThem) {
    EXPECT_EQ(*nss_ratio_folder(2.0), "x2");
    EXPECT_EQ(*nss_ratio_folder(1.5), "x1_5");
    EXPECT_EQ(*nss_ratio_folder(1.7), "x1_7");
    EXPECT_EQ(*nss_ratio_folder(1.3), "x1_3");
    EXPECT_EQ(*nss_ratio_folder(3.0), "x3");
    EXPECT_FALSE(nss_ratio_folder(1.05)); // Arm's reader would look in "x15"
    EXPECT_FALSE(nss_ratio_folder(0.5));
    EXPECT_FALSE(nss_ratio_folder(NAN));
}

// The input may be TargetResolution / ratio rounded down or to the nearest: 33x19 / 2 = 16.5x9.5.
TEST(NssCapture, AnOddTargetTakesEitherRounding) {
    for (int w : {16, 17}) {
        Capture c;
        json spec = default_spec();
        spec["target"] = {33, 19};
        spec["input"] = {w, w == 16 ? 9 : 10};
        write_capture(c, spec);
        auto capture = read_nss_capture(c.root(), "0000", 2.0);
        ASSERT_TRUE(capture) << capture.error().message;
        EXPECT_EQ(capture->input_width, std::uint32_t(w));
    }
}

// Each refusal names the file (or folder) and the field.
void expect_refused(const Capture& c, double ratio, std::initializer_list<std::string> named) {
    auto capture = read_nss_capture(c.root(), "0000", ratio);
    ASSERT_FALSE(capture) << "accepted";
    for (const std::string& part : named)
        EXPECT_NE(capture.error().message.find(part), std::string::npos)
            << "'" << part << "' not in: " << capture.error().message;
}

TEST(NssCapture, RefusesARatioWithoutItsIndexOrFolder) {
    Capture c;
    write_capture(c, default_spec());
    json meta = read_json(c.json_file());
    meta["UpscalingRatiosIndices"].erase("x1_7_index");
    write_json(c.json_file(), meta);
    expect_refused(c, 1.7, {c.json_file().string(), "UpscalingRatiosIndices", "x1_7_index"});
    expect_refused(c, 1.5, {(c.root() / "x1_5").string(), "missing"}); // indexed, but no folder
}

TEST(NssCapture, RefusesAColorOfTheWrongSize) {
    Capture c;
    json spec = default_spec();
    spec["input"] = {15, 9};
    write_capture(c, spec);
    expect_refused(c, 2.0, {(c.root() / "x2/color/0000/0000.exr").string(), "15x9", "TargetResolution"});
}

TEST(NssCapture, RefusesAReferenceOfTheWrongSize) {
    Capture c;
    write_capture(c, default_spec());
    json meta = read_json(c.json_file());
    meta["TargetResolution"]["X"] = 30;
    write_json(c.json_file(), meta);
    expect_refused(c, 2.0, {(c.root() / "ground_truth/0000/0000.exr").string(), "TargetResolution"});
}

TEST(NssCapture, RefusesAMissingFolderOrFrame) {
    {
        Capture c;
        write_capture(c, default_spec());
        fs::remove_all(c.root() / "x2/depth/0000");
        expect_refused(c, 2.0, {(c.root() / "x2/depth/0000").string(), "missing"});
    }
    {
        Capture c;
        write_capture(c, default_spec());
        fs::remove(c.root() / "x2/motion/0000/0002.exr");
        expect_refused(c, 2.0, {(c.root() / "x2/motion/0000").string(), "5 frames", "6"});
    }
    {
        Capture c;
        write_capture(c, default_spec());
        // The right root, a sequence it does not have.
        auto other = read_nss_capture(c.root(), "0001", 2.0);
        ASSERT_FALSE(other);
        EXPECT_NE(other.error().message.find("0001.json"), std::string::npos) << other.error().message;
    }
}

TEST(NssCapture, RefusesANonFiniteJitter) {
    Capture c;
    write_capture(c, default_spec());
    // Python's json writes NaN as the bare literal NaN, which Arm's loader reads.
    std::string text = test::read_file(c.json_file());
    const std::string x2 = fmt::format("\"X\": {}", 0.25 / 16);
    // Frame 2's x2 entry: the third occurrence of its X.
    std::size_t at = 0;
    for (int i = 0; i < 3; ++i) at = text.find(x2, at + (i ? 1 : 0));
    ASSERT_NE(at, std::string::npos) << text.substr(0, 2000);
    text.replace(at, x2.size(), "\"X\": NaN");
    test::write_file(c.json_file(), text);
    expect_refused(c, 2.0, {c.json_file().string(), "Frames[2].NormalizedPerRatioJitter[1].X", "NaN", "finite"});
}

TEST(NssCapture, RefusesFewerJsonFramesThanFilesButTakesMore) {
    Capture c;
    write_capture(c, default_spec());
    json meta = read_json(c.json_file());
    json more = meta;
    more["Frames"].push_back(more["Frames"][0]); // Arm's own fixture lists 100 frames over 1 file
    write_json(c.json_file(), more);
    auto capture = read_nss_capture(c.root(), "0000", 2.0);
    ASSERT_TRUE(capture) << capture.error().message;
    EXPECT_EQ(capture->frames.size(), 6u);
    meta["Frames"].erase(5);
    write_json(c.json_file(), meta);
    expect_refused(c, 2.0, {c.json_file().string(), "Frames lists 5 frames", "6 files"});
}

TEST(NssCapture, RefusesMalformedJson) {
    Capture c;
    write_capture(c, default_spec());
    const json meta = read_json(c.json_file());
    json no_target = meta;
    no_target.erase("TargetResolution");
    write_json(c.json_file(), no_target);
    expect_refused(c, 2.0, {c.json_file().string(), "TargetResolution"});
    json bad_cut = meta;
    bad_cut["Frames"][1]["CameraCut"] = "yes";
    write_json(c.json_file(), bad_cut);
    expect_refused(c, 2.0, {c.json_file().string(), "Frames[1].CameraCut"});
    json bad_exposure = meta;
    bad_exposure["Frames"][4]["Exposure"] = -1.0;
    write_json(c.json_file(), bad_exposure);
    expect_refused(c, 2.0, {c.json_file().string(), "Frames[4].Exposure"});
    json bad_reverse = meta;
    bad_reverse["ReverseZ"] = 1;
    write_json(c.json_file(), bad_reverse);
    expect_refused(c, 2.0, {c.json_file().string(), "ReverseZ"});
    test::write_file(c.json_file(), "{\"TargetResolution\": ");
    expect_refused(c, 2.0, {c.json_file().string(), "not JSON"});
}

// kdop taa on a tiny capture: 32x18 output, 16x9 input, 6 frames, measured against its ground truth.
TEST(CliNss, TaaMeasuresACaptureAgainstItsGroundTruth) {
    Capture c;
    write_capture(c, default_spec());
    const fs::path out = c.dir / "out";
    auto taa = test::run({test::kdop_binary(), "taa", "--sequence", c.root().string(), "--nss-sequence", "0000",
                          "--ratio", "2", "--sets", "aabb", "--modes", "clip", "--warmup", "2", "--viewer-frames", "0",
                          "--no-charts", "--out", out.string()});
    ASSERT_EQ(taa.exit_code, 0) << taa.err;
    const auto rows = test::csv_rows(test::read_file(out / "taa.csv"));
    ASSERT_EQ(rows.size(), 2u) << "the variant, and the spatial-only upscale of the capture";
    EXPECT_EQ(rows[1].at("variant"), "spatial-lanczos2");
    EXPECT_EQ(rows[0].at("upscale"), "2");
    EXPECT_EQ(rows[0].at("scene"), "0000");
    EXPECT_EQ(rows[0].at("ghosting_against"), "reference");
    EXPECT_EQ(rows[0].at("flip"), "HDR-FLIP");
    ASSERT_FALSE(rows[0].at("ghosting").empty());
    const double ghosting = std::stod(rows[0].at("ghosting"));
    EXPECT_TRUE(std::isfinite(ghosting) && ghosting >= 0.0) << ghosting;
    EXPECT_TRUE(fs::exists(out / "ghosting-0000.png"));
}

// --nss-range ldr: the capture measured in LDR-FLIP, a value above 1 (the bright dot, 4) refused
// naming its file and pixel, never clamped.
TEST(NssCapture, AnLdrRangeRefusesAValueOutsideZeroToOne) {
    Capture c;
    write_capture(c, default_spec());
    auto capture = read_nss_capture(c.root(), "0000", 2.0);
    ASSERT_TRUE(capture) << capture.error().message;
    const NssFrames frames(std::move(*capture), ColorRange::ldr);
    EXPECT_EQ(frames.color_range(), ColorRange::ldr);
    auto frame = frames.frame(0);
    ASSERT_FALSE(frame);
    const std::string& message = frame.error().message;
    EXPECT_NE(message.find((c.root() / "x2" / "color" / "0000" / "0000.exr").string() + ": pixel (3, 1) has R 4"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("--nss-range hdr"), std::string::npos) << message;
}

TEST(CliNss, OptionsThatDoNotGoTogetherAreUsageErrors) {
    Capture c;
    write_capture(c, default_spec());
    const fs::path out = c.dir / "out";
    auto ratio_alone =
        test::run({test::kdop_binary(), "taa", "--sequence", c.root().string(), "--ratio", "2", "--out", out.string()});
    EXPECT_EQ(ratio_alone.exit_code, 2) << ratio_alone.err;
    EXPECT_NE(ratio_alone.err.find("--nss-sequence"), std::string::npos) << ratio_alone.err;
    auto no_root = test::run({test::kdop_binary(), "taa", "--nss-sequence", "0000", "--out", out.string()});
    EXPECT_EQ(no_root.exit_code, 2) << no_root.err;
    EXPECT_NE(no_root.err.find("--sequence"), std::string::npos) << no_root.err;
    auto range_alone = test::run(
        {test::kdop_binary(), "taa", "--sequence", c.root().string(), "--nss-range", "ldr", "--out", out.string()});
    EXPECT_EQ(range_alone.exit_code, 2) << range_alone.err;
    EXPECT_NE(range_alone.err.find("--nss-range"), std::string::npos) << range_alone.err;
    auto unindexed = test::run({test::kdop_binary(), "taa", "--sequence", c.root().string(), "--nss-sequence", "0000",
                                "--ratio", "1.05", "--out", out.string()});
    EXPECT_EQ(unindexed.exit_code, 2) << unindexed.err;
    EXPECT_NE(unindexed.err.find("--ratio"), std::string::npos) << unindexed.err;
}

} // namespace
} // namespace kdop
