#include "sequence/nss_writer.h"

#include "sequence/frame_cache.h"
#include "sequence/nss_capture.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <set>
#include <utility>

// The conventions are nss_capture.cpp's, inverted; its comments give the evidence in Arm's
// repository for each.

namespace kdop {
namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

// The spec's Version this layout follows (docs/nss/nss_dataset_specification.md; Arm's reader is
// registered as "NSSv1_0_1").
constexpr const char* kSpecVersion = "1.0.1";
// EmulatedFramerate: mandatory, an int. kdop's scenes step their animation once a frame and have
// no clock, so this is nominal (docs/taa.md, "NSS captures"); nothing in kdop reads it.
constexpr int kNominalFramerate = 60;

// Frame files are paired by sorted name (nss_capture.cpp's exr_files): four digits, as the spec
// shows, or as many as the last frame's number needs, so that the names sort in frame order.
std::string frame_file(std::size_t index, std::size_t count) {
    const int digits = std::max<int>(4, int(fmt::format("{}", count > 0 ? count - 1 : 0).size()));
    return fmt::format("{:0{}}.exr", index, digits);
}

// Color as NSS stores it: RGB linear, alpha 1 (the capture guide's decimation writes 1).
Image opaque(const Image& image) {
    Image out = image;
    for (glm::vec4& p : out.pixels) p.a = 1.0f;
    return out;
}

// Motion in NSS's UV (nss_motion), R and G; zero where the frame has none (a first frame).
Image uv_motion_image(const std::vector<glm::vec2>& motion, std::uint32_t width, std::uint32_t height) {
    Image out(width, height, glm::vec4(0, 0, 0, 1));
    if (motion.size() == out.pixels.size())
        for (std::size_t i = 0; i < motion.size(); ++i)
            out.pixels[i] = glm::vec4(nss_motion(motion[i], width, height), 0, 1);
    return out;
}

// NormalizedPerRatioJitter's value: the offset from the pixel's center over the input size, in
// double, so that nss_capture.cpp's `float(x * width)` gives back the float exactly.
ordered_json normalized(glm::vec2 jitter, std::uint32_t width, std::uint32_t height) {
    return {{"X", double(jitter.x) / double(width)}, {"Y", double(jitter.y) / double(height)}};
}

} // namespace

glm::vec2 nss_motion(glm::vec2 motion, std::uint32_t width, std::uint32_t height) {
    // nss_capture.cpp reads m = -(v * size) in float. The nearest float to -m / size gives m back
    // exactly at a size that is a power of two, and for 92.7% of motions at others (a million
    // random ones, NssWriter.MotionReadsBackExactlyOrWithinAFloatStep), the rest one float step
    // away: then no float gives m back (its neighbors were tried: none ever did), since v * size
    // steps over some floats when size is not a power of two.
    return -motion / glm::vec2{float(width), float(height)};
}

std::string nss_sequence_number(std::size_t index) { return fmt::format("{:04}", index); }

std::string nss_sequences_json(const std::vector<std::shared_ptr<const FrameSource>>& sources) {
    ordered_json list = ordered_json::array();
    for (std::size_t s = 0; s < sources.size(); ++s) {
        ordered_json entry{{"sequence", nss_sequence_number(s)}, {"name", sources[s]->name()}};
        if (const SequenceRoles roles = sources[s]->roles(); roles != SequenceRoles{}) {
            ordered_json measure = ordered_json::array();
            if (roles.ghosting) measure.push_back("ghosting");
            if (roles.shimmer) measure.push_back("shimmer");
            entry["measure"] = std::move(measure);
        }
        list.push_back(std::move(entry));
    }
    return list.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

Result<void> check_nss_writable(const FrameSource& source, const NssWriteOptions& options) {
    if (auto folder = nss_ratio_folder(options.ratio, options.ratio_option); !folder)
        return std::unexpected(folder.error());
    if (!source.has_reference())
        return usage_fail(fmt::format("{}: has no reference frames; every frame of an NSS capture has its ground "
                                      "truth",
                                      source.name()));
    if (!source.has_output_motion())
        return usage_fail(fmt::format("{}: has no motion at the output size; every frame of an NSS capture has its "
                                      "motion_gt",
                                      source.name()));
    return {};
}

std::string nss_sequence_json(const FrameSource& source, const NssWriteOptions& options) {
    const std::string folder = nss_ratio_folder(options.ratio, options.ratio_option).value_or("x?");
    const std::uint32_t w = source.input_width(), h = source.input_height();
    // Samples.Count: "the number of unique positions" of the jitter.
    std::set<std::pair<float, float>> positions;
    for (std::size_t i = 0; i < source.frame_count(); ++i) {
        const glm::vec2 j = source.jitter(i).value_or(glm::vec2(0));
        positions.insert({j.x, j.y});
    }
    ordered_json samples;
    if (!options.sample_sequence.empty()) samples["Sequence"] = options.sample_sequence;
    samples["Count"] = positions.size();
    samples["Quantized"] = false;

    ordered_json root{{"Version", kSpecVersion},
                      {"EmulatedFramerate", kNominalFramerate},
                      {"TargetResolution", {{"X", source.width()}, {"Y", source.height()}}},
                      {"Samples", std::move(samples)},
                      // kdop's depth is forward: 0 near, 1 far (testbed/camera.h).
                      {"ReverseZ", false},
                      {"UpscalingRatiosIndices", {{folder + "_index", 0}}},
                      // motion_gt is drawn at each output pixel's center, not dilated.
                      {"MotionVectorsDilated", false}};
    ordered_json frames = ordered_json::array();
    for (std::size_t i = 0; i < source.frame_count(); ++i) {
        ordered_json f{{"Frame", i}};
        if (const auto camera = source.camera_of(i)) {
            f["FovX"] = camera->fov_x;
            f["FovY"] = camera->fov_y;
            f["CameraNearPlane"] = camera->near_plane;
            f["CameraFarPlane"] = camera->far_plane;
            // The matrix's rows one after another: Arm's reader reshapes the 16 values into a
            // 4x4 row by row and uses it as clip = M p (nss_exr_dataset_reader.py, "viewProj").
            ordered_json m = ordered_json::array();
            for (int row = 0; row < 4; ++row)
                for (int column = 0; column < 4; ++column) m.push_back(camera->view_projection[column][row]);
            f["ViewProjection"] = std::move(m);
        }
        const glm::vec2 jitter = source.jitter(i).value_or(glm::vec2(0));
        f["Jitter"] = {{"X", jitter.x}, {"Y", jitter.y}}; // input pixels
        f["NormalizedPerRatioJitter"] = ordered_json::array({normalized(jitter, w, h)});
        // The first frame too, as Arm's capture guide sets it: nothing before it is a history.
        f["CameraCut"] = source.starts_history(i);
        // kdop's colors are not exposed: the multiplier is 1.
        f["Exposure"] = 1.0;
        frames.push_back(std::move(f));
    }
    root["Frames"] = std::move(frames);
    return root.dump(1, '\t', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::vector<OutputWriter> nss_frame_writers(const fs::path& root, const std::string& sequence,
                                            std::shared_ptr<const FrameSource> source, const NssWriteOptions& options) {
    const std::string folder = nss_ratio_folder(options.ratio, options.ratio_option).value_or("x?");
    auto cache = std::make_shared<FrameCache>();
    cache->source = source;
    const FloatPrecision precision = options.precision;
    const std::uint32_t w = source->input_width(), h = source->input_height();
    const std::uint32_t out_w = source->width(), out_h = source->height();
    static constexpr const char* kMotion[] = {"R", "G"};
    static constexpr const char* kDepth[] = {"R"}; // Arm's reader reads depth's channel "R"
    std::vector<OutputWriter> writers;
    const std::size_t count = source->frame_count();
    for (std::size_t i = 0; i < count; ++i) {
        // `write` writes the frame's file of that stream at `to`, given the frame.
        auto add = [&](const fs::path& dir, auto write) {
            const fs::path path = dir / frame_file(i, count);
            writers.push_back({path, [cache, i, write, path](const fs::path& to) -> Result<void> {
                                   auto frame = cache->get(i);
                                   if (!frame) return std::unexpected(frame.error());
                                   return write(**frame, to, path.string());
                               }});
        };
        const fs::path input = root / folder;
        add(input / "color" / sequence,
            [precision](const LoadedFrame& f, const fs::path& to, const std::string& path) -> Result<void> {
                return write_image_to(to, path, opaque(f.color), precision);
            });
        add(input / "depth" / sequence,
            [i, cache](const LoadedFrame& f, const fs::path& to, const std::string& path) -> Result<void> {
                if (!f.depth)
                    return fail(fmt::format("{}: frame {} of {} has no depth", path, i, cache->source->name()));
                return write_data_image_to(to, path, *f.depth, kDepth, FloatPrecision::full);
            });
        add(input / "motion" / sequence,
            [w, h, precision](const LoadedFrame& f, const fs::path& to, const std::string& path) -> Result<void> {
                return write_data_image_to(to, path, uv_motion_image(f.motion, w, h), kMotion, precision);
            });
        add(root / "ground_truth" / sequence,
            [i, cache, precision](const LoadedFrame& f, const fs::path& to, const std::string& path) -> Result<void> {
                if (!f.reference)
                    return fail(fmt::format("{}: frame {} of {} has no reference", path, i, cache->source->name()));
                return write_image_to(to, path, opaque(*f.reference), precision);
            });
        // Drawn apart from the frame, at the output size.
        add(root / "motion_gt" / sequence,
            [i, cache, out_w, out_h, precision](const LoadedFrame&, const fs::path& to,
                                                const std::string& path) -> Result<void> {
                auto motion = cache->source->output_motion(i);
                if (!motion) return fail(fmt::format("{}: {}", path, motion.error().message));
                return write_data_image_to(to, path, uv_motion_image(*motion, out_w, out_h), kMotion, precision);
            });
    }
    return writers;
}

} // namespace kdop
