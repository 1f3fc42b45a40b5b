// What `kdop taa` measures, gathered and checked before any frame is made or read: frame sequences
// from disk and kdop's own scenes, every size checked against the device and memory, every name
// distinct (a row is named after its source).
#pragma once

#include "core/result.h"
#include "images/image_io.h"
#include "runtime/context.h"
#include "scenes/scene_catalog.h"
#include "scenes/taa_scene.h"
#include "sequence/frame_source.h"
#include "sequence/nss_capture.h"
#include "temporal/resolve_options.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace kdop {

// What is measured: kdop's scenes, then the frame sequences.
struct TaaSources {
    std::vector<std::shared_ptr<const TaaScene>> scenes;
    std::vector<SequenceFrames> sequences;
    std::vector<NssFrames> captures; // NSS captures (sequence/nss_capture.h), measured as sequences are

    std::size_t size() const { return scenes.size() + sequences.size() + captures.size(); }
    bool any_hdr() const; // a sequence measured in HDR-FLIP (an NSS capture but under --nss-range ldr)
};

struct TaaSourceRequest {
    std::vector<std::string> sequences; // folders
    std::uint32_t warmup = 100;         // frames every sequence must have more of
    ResolveOptions resolve;             // what the resolve needs of a sequence (depth for --dilate-motion)
    bool own_reads_depth = false;       // a renderer's resolve (--resolve) reads depth: an NSS capture's is kept
    InputSpace input_space = InputSpace::from_file;
    bool device_flip = true;  // FLIP on the device: its limits count too
    std::size_t variants = 1; // resolved together in one pass: each holds its history in memory
    // kdop's scenes, made at options' size (checked first); none when `builtin` is false.
    bool builtin = true;
    std::vector<std::string> scene_names, backgrounds; // scene_catalog.h's select_taa_scenes
    SceneOptions scene_options;                        // its context is filled in
    // --picture-frame: a measured frame of every sequence that has a ghosting picture (those meant
    // for ghosting), checked here.
    std::optional<std::size_t> picture_frame;
    std::string option = "--sequence"; // the option that gave the sequences, for errors
    // --nss-sequence: each folder of `sequences` is then an NSS capture's root, and this sequence
    // of it is read at upscaling ratio `nss_ratio` (sequence/nss_capture.h).
    std::string nss_sequence;
    double nss_ratio = 2.0;
    // --nss-range: the range the capture's colors keep to, and so the FLIP it is measured in.
    ColorRange nss_range = ColorRange::hdr;
};

// Reads the sequences, then makes the scenes. Errors name the option and folder; Error::usage
// where the command line is at fault (a size the device cannot measure, a folder given twice).
Result<TaaSources> taa_sources(const Context& context, TaaSourceRequest request);

} // namespace kdop
