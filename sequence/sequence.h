// A frame sequence: the contract between every content source (kdop's own scenes, a renderer's
// captured frames, Blender, a 3-D testbed) and the one TAA resolve. A folder holds sequence.json
// and per-frame EXR files; docs/taa.md, "Frame sequences", documents the format, version 1:
//
//     {"kdop_sequence": 1, "width": 320, "height": 180, "color": {"range": "ldr"}, "measure": ["ghosting"],
//      "motion": {"units": "pixels", "points_to": "previous", "y_axis": "down"},
//      "depth": {"nearer": "smaller"},
//      "frames": [{"color": "color/0000.exr", "motion": "motion/0000.exr", "jitter": [0.12, -0.31],
//                  "depth": "depth/0000.exr", "reference": "reference/0000.exr", "camera_cut": false}]}
//
// read_sequence() reads and checks sequence.json, that every file it names is a regular file inside
// the folder, and that the first frame's header gives the declared size, and reads no pixel: a
// 400-frame 1920x1080 sequence costs its list of names.
// load_frame() reads one frame's files when the resolve needs them, checks them against the
// sequence (size, channels, finite values) and turns the motion into one convention; peak memory
// is a frame's, whatever the frame count. Every error names the file (sequence.json with its line
// and column, or the JSON path of the value) and the reason.
#pragma once

#include "core/result.h"
#include "images/image.h"
#include "images/image_io.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

inline constexpr int kSequenceFormatVersion = 1;

// What a sequence's color and reference files hold, and so what ghosting and shimmer are measured
// in: `ldr`, linear values from 0 to 1, in LDR-FLIP; `hdr`, linear values from 0 up, in HDR-FLIP.
enum class ColorRange { ldr, hdr };
const char* to_string(ColorRange range); // "ldr", "hdr"

// How a sequence's motion files are to be read. Whatever they say, load_frame() gives motion in
// pixels, pointing to where the surface at the pixel's center was in the previous frame, y down.
struct MotionConvention {
    enum class Units { pixels, uv };           // uv: divided by the frame's width and height
    enum class PointsTo { previous, current }; // current: the velocity convention of Unreal and Unity
    enum class YAxis { down, up };
    Units units = Units::pixels;
    PointsTo points_to = PointsTo::previous;
    YAxis y_axis = YAxis::down;
};

// Which figures a sequence is meant for ("measure" in sequence.json; both by default): a still,
// jittered capture shows shimmer and no meaningful ghosting, a moving one without jitter ghosting
// and no meaningful shimmer. A figure a sequence is not meant for is not measured or shown.
struct SequenceRoles {
    bool ghosting = true, shimmer = true;
    friend bool operator==(const SequenceRoles&, const SequenceRoles&) = default;
};

struct SequenceFrame {
    std::filesystem::path color;            // linear RGB in the first three channels, any range
    std::filesystem::path motion;           // empty only where there is no history to reproject
    std::filesystem::path depth, reference; // optional: empty when not given
    std::optional<glm::vec2> jitter;        // the sample's offset from the pixel center, pixels
    bool camera_cut = false;                // the history is dropped before this frame
};

struct Sequence {
    std::filesystem::path dir;
    std::string name;                    // the folder's name, for tables
    std::uint32_t width = 0, height = 0; // the frames' color, motion and depth
    // "output": {"width", "height"}: frames drawn for temporal upscaling, resolved to this size,
    // their references at it (docs/taa.md, "Upscaling"); 0: the frames' own size.
    std::uint32_t output_width = 0, output_height = 0;
    bool upscales() const { return output_width != 0 && (output_width != width || output_height != height); }
    // "color": {"range": "ldr" | "hdr"}: the range the color and reference files keep to. Reading
    // a frame does not check it (every finite value is read); the measurement does.
    ColorRange color_range = ColorRange::ldr;
    MotionConvention motion;
    // "depth": {"nearer": "smaller" | "larger"}: which way depth files count (larger: reversed Z,
    // as Unreal writes it). Only --dilate-motion reads depth.
    bool depth_nearer_larger = false;
    SequenceRoles measure;
    std::vector<SequenceFrame> frames; // paths joined to dir

    // Whether frame `index` starts without a history: the first frame and every camera cut.
    bool starts_history(std::size_t index) const { return index == 0 || frames[index].camera_cut; }
};

// Reads `dir`/sequence.json. Refuses a wrong version, unknown keys (a misspelled "point_to" must
// not silently mean the default), a frame without color, a frame with a history but no motion, a
// jitter outside [-0.5, 0.5], and any named file that is missing, not a regular file, or outside
// the folder.
Result<Sequence> read_sequence(const std::filesystem::path& dir);

// Fails, a usage error naming `option` and the file, when a file of `sequence` (sequence.json or a
// frame's, its links followed) lies inside the folder `out`, where a run writes its outputs: one
// of them could replace it, found only when the set is written, after all the work, and a file an
// earlier run listed there could be removed as that run's. Checked before the work instead.
Result<void> check_outside(const Sequence& sequence, const std::filesystem::path& out, std::string_view option);

// One frame's images, as the resolve takes them.
struct LoadedFrame {
    Image color;                    // linear RGB, alpha 1
    std::vector<glm::vec2> motion;  // per pixel, row-major: pixels, to the previous frame, y down; empty at a start
    std::optional<Image> depth;     // depth in the red channel
    std::optional<Image> reference; // linear RGB
    // Where the frame's samples lie: pixel i's at i + 0.5 + jitter (pixels, y down). What an
    // upscaling resolve reconstructs the output from; a resolve at the frame's size ignores it.
    glm::vec2 jitter{0.0f};
};

// Reads frame `index` of `sequence`. `space` decodes color and reference files (EXR is linear
// whatever it says); motion and depth are data, read as stored. With `depth` false the depth file
// is not read (the frame has none): for a resolve that does not read depth.
Result<LoadedFrame> load_frame(const Sequence& sequence, std::size_t index, InputSpace space = InputSpace::from_file,
                               bool depth = true);

// Only frame `index`'s color, checked as load_frame() checks it: what a fit to the sequence reads.
Result<Image> load_frame_color(const Sequence& sequence, std::size_t index, InputSpace space = InputSpace::from_file);

// The motion of one pixel, as stored in a file of `convention`, in load_frame()'s convention.
glm::vec2 canonical_motion(glm::vec2 stored, const MotionConvention& convention, std::uint32_t width,
                           std::uint32_t height);

} // namespace kdop
