// Any frame source written in Arm's NSS dataset capture layout (the layout nss_capture.h reads):
// `kdop scene --layout nss` writes kdop's own scenes this way, so a capture made by kdop can be
// read by kdop taa --nss-sequence and by Arm's tools. Each sequence is
//
//     ROOT/NNNN.json                              per-sequence and per-frame metadata
//     ROOT/ground_truth/NNNN/0000.exr ...         the reference, at the output size
//     ROOT/motion_gt/NNNN/0000.exr ...            motion at the output size, without jitter
//     ROOT/x{ratio}/{color,depth,motion}/NNNN/... the frames, at the input size
//
// in the conventions docs/taa.md, "NSS captures", gives: each exactly the inverse of what
// nss_capture.cpp reads, so reading a written sequence back gives the source's frames.
#pragma once

#include "core/result.h"
#include "core/write_files.h"
#include "images/image_io.h"
#include "sequence/frame_source.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace kdop {

struct NssWriteOptions {
    double ratio = 1; // the source's upscaling ratio (output over input size), which names x{ratio}
    // Color, ground truth, motion and motion_gt: half floats (the spec's R16G16B16A16_SFLOAT and
    // R16G16_SFLOAT) or full; depth is always full (R32_SFLOAT).
    FloatPrecision precision = FloatPrecision::half;
    std::string sample_sequence = {}; // Samples.Sequence: how the jitter was chosen ("Halton(2,3)"); empty: left out
    std::string ratio_option = "--upscale"; // the option that gave `ratio`, for errors
};

// Why `source` cannot be written as an NSS sequence, if it cannot (Error::usage): every NSS frame
// has a ground truth and a motion_gt, so a source without references or without motion at the
// output size is refused; so is a ratio NSS cannot name (nss_ratio_folder).
Result<void> check_nss_writable(const FrameSource& source, const NssWriteOptions& options);

// NNNN.json for `source` (TargetResolution, Samples, ReverseZ false, UpscalingRatiosIndices and
// per frame Frame, the camera where the source has one, Jitter, NormalizedPerRatioJitter,
// CameraCut and Exposure 1). Deterministic: the same source gives the same bytes.
std::string nss_sequence_json(const FrameSource& source, const NssWriteOptions& options);

// The writers of every frame's files of sequence `sequence` ("0000") under the dataset root `root`
// (NNNN.json not included), for a set written all or nothing (core/write_files.h). Each frame is
// made when its first file is written and dropped after its last. check_nss_writable first.
std::vector<OutputWriter> nss_frame_writers(const std::filesystem::path& root, const std::string& sequence,
                                            std::shared_ptr<const FrameSource> source, const NssWriteOptions& options);

// The name of a dataset's sequence `index`, as the spec numbers them: "0000", "0001", ...
std::string nss_sequence_number(std::size_t index);

// kdop_sequences.json, beside the NNNN.json files: which of `sources` became which number (the
// order given), and what kdop measures on it ("measure", as sequence.json's). Arm's tools read
// only NNNN.json and find sequences by the folders that hold EXR files, so it is no sequence.
inline constexpr const char* kNssSequencesFile = "kdop_sequences.json";
std::string nss_sequences_json(const std::vector<std::shared_ptr<const FrameSource>>& sources);

// kdop's motion (pixels toward the previous position, y down, of an image `width` x `height`) as
// NSS stores it: UV now minus UV before, in units of the image's size, v down: -motion / size,
// which nss_capture.cpp's reading (times the size, negated) turns back into `motion` exactly or
// one float step away (see nss_writer.cpp).
glm::vec2 nss_motion(glm::vec2 motion, std::uint32_t width, std::uint32_t height);

} // namespace kdop
