// Arm's NSS dataset capture layout (Neural Super Sampling; arm/neural-graphics-model-gym,
// docs/nss/nss_dataset_specification.md) read as a frame source, so that `kdop taa` measures the
// resolve on a capture as it is written, without converting it:
//
//     ROOT/NNNN.json                              per-sequence and per-frame metadata
//     ROOT/ground_truth/NNNN/0000.exr ...         the reference, at TargetResolution
//     ROOT/x{ratio}/{color,depth,motion}/NNNN/... the renderer's frames, at TargetResolution / ratio
//
// read_nss_capture() reads and checks NNNN.json, lists the folders and checks each stream's first
// header (sizes), reading no pixel; NssFrames::frame() reads one frame's files and turns them into
// kdop's conventions (sequence.h's LoadedFrame). docs/taa.md, "NSS captures", gives each convention
// with its evidence in Arm's reader.
#pragma once

#include "core/result.h"
#include "sequence/frame_source.h"

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

// The folder of upscaling ratio `ratio` as Arm's reader names it (nss_exr_dataset_reader.py,
// `str(float(scale)).replace(".", "_").replace("_0", "")`): 2 -> "x2", 1.5 -> "x1_5", 1.7 -> "x1_7".
// Refuses a ratio below 1, above 8 or not finite; and one of more than one decimal, which Arm's
// name mangles (1.05 -> "x15").
// Errors name `option`, the option that gave the ratio.
Result<std::string> nss_ratio_folder(double ratio, std::string_view option = "--ratio");

struct NssFrame {
    std::filesystem::path color, depth, motion, reference;
    glm::vec2 jitter{0.0f};  // input pixels, kdop's sign: the sample lies at i + 0.5 + jitter, y down
    bool camera_cut = false; // "CameraCut"
    float exposure = 1.0f;   // "Exposure", the linear multiplier of color and reference (1 when absent)
};

struct NssCapture {
    std::filesystem::path root;
    std::string sequence;                            // "0000"
    std::string ratio_folder;                        // "x2"
    std::uint32_t width = 0, height = 0;             // TargetResolution: the reference's, the output's
    std::uint32_t input_width = 0, input_height = 0; // the color files'
    bool reverse_z = false;                          // "ReverseZ": depth read as 1 - stored
    std::vector<NssFrame> frames;
};

// Reads sequence `sequence` of the capture at `root` at upscaling ratio `ratio`. Refuses, naming
// the file and the field: JSON that is malformed or lacks a field kdop uses, a ratio missing from
// UpscalingRatiosIndices or its folder missing, a missing stream folder or frame (streams of
// different counts), fewer JSON frames than files, a non-finite jitter or exposure, and files of a
// size other than the spec's.
Result<NssCapture> read_nss_capture(const std::filesystem::path& root, const std::string& sequence, double ratio);

// Fails, a usage error naming `option`, when a file of `capture` lies inside `out`, where a run
// writes its outputs (as check_outside in sequence.h).
Result<void> check_outside(const NssCapture& capture, const std::filesystem::path& out, std::string_view option);

class NssFrames final : public FrameSource {
public:
    // `range`: hdr (what NSS captures are, the spec's "linear HDR"), measured in HDR-FLIP; or ldr,
    // for a capture whose values lie in [0, 1] (kdop's own scenes written by `kdop scene --layout
    // nss`), measured in LDR-FLIP: frame() then refuses a color or ground truth value outside
    // [0, 1], after the exposure, naming its file and pixel (never clamped).
    explicit NssFrames(NssCapture capture, ColorRange range = ColorRange::hdr)
        : c_(std::move(capture)), name_(c_.sequence), range_(range) {}
    const NssCapture& capture() const { return c_; }
    // The same frames read without their depth files, for a resolve that does not read depth.
    NssFrames without_depth() const {
        NssFrames s = *this;
        s.depth_ = false;
        return s;
    }

    const std::string& name() const override { return name_; }
    std::uint32_t width() const override { return c_.width; }
    std::uint32_t height() const override { return c_.height; }
    std::uint32_t input_width() const override { return c_.input_width; }
    std::uint32_t input_height() const override { return c_.input_height; }
    std::size_t frame_count() const override { return c_.frames.size(); }
    ColorRange color_range() const override { return range_; }
    bool starts_history(std::size_t index) const override { return index == 0 || c_.frames[index].camera_cut; }
    std::optional<glm::vec2> jitter(std::size_t index) const override { return c_.frames[index].jitter; }
    bool has_depth() const override { return depth_; }
    bool has_reference() const override { return true; }
    Result<LoadedFrame> frame(std::size_t index) const override;
    std::string frame_label(std::size_t index) const override;
    bool reads_ahead() const override { return true; }

private:
    NssCapture c_;
    std::string name_;
    ColorRange range_;
    bool depth_ = true;
};

} // namespace kdop
