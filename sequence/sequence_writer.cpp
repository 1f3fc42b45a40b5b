#include "sequence/sequence_writer.h"

#include "images/image_io.h"
#include "sequence/frame_cache.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace kdop {
namespace {

std::string frame_file(const char* kind, std::size_t index) { return fmt::format("{}/{:04}.exr", kind, index); }

Image motion_image(const std::vector<glm::vec2>& motion, std::uint32_t width, std::uint32_t height) {
    Image out(width, height);
    for (std::size_t i = 0; i < motion.size(); ++i) out.pixels[i] = glm::vec4(motion[i], 0, 1);
    return out;
}

} // namespace

std::string sequence_json(const FrameSource& source) {
    using nlohmann::ordered_json;
    ordered_json root{
        {"kdop_sequence", kSequenceFormatVersion}, {"width", source.input_width()}, {"height", source.input_height()}};
    if (source.upscales()) root["output"] = {{"width", source.width()}, {"height", source.height()}};
    root["color"] = {{"range", to_string(source.color_range())}};
    // What the sequence is meant for, where not both: kdop's scenes' still and moving sequences.
    if (const SequenceRoles roles = source.roles(); roles != SequenceRoles{}) {
        ordered_json measure = ordered_json::array();
        if (roles.ghosting) measure.push_back("ghosting");
        if (roles.shimmer) measure.push_back("shimmer");
        root["measure"] = std::move(measure);
    }
    root["motion"] = {{"units", "pixels"}, {"points_to", "previous"}, {"y_axis", "down"}};
    ordered_json frames = ordered_json::array();
    for (std::size_t i = 0; i < source.frame_count(); ++i) {
        ordered_json f{{"color", frame_file("color", i)}};
        if (!source.starts_history(i)) f["motion"] = frame_file("motion", i);
        if (source.has_depth()) f["depth"] = frame_file("depth", i);
        if (source.has_reference()) f["reference"] = frame_file("reference", i);
        if (const auto jitter = source.jitter(i)) f["jitter"] = {jitter->x, jitter->y};
        if (i > 0 && source.starts_history(i)) f["camera_cut"] = true;
        frames.push_back(std::move(f));
    }
    root["frames"] = std::move(frames);
    return root.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::vector<OutputWriter> sequence_frame_writers(const std::filesystem::path& folder,
                                                 std::shared_ptr<const FrameSource> source) {
    auto cache = std::make_shared<FrameCache>();
    cache->source = source;
    std::vector<OutputWriter> writers;
    const std::uint32_t w = source->input_width(), h = source->input_height(); // the motion's
    // Color is RGBA (no data channels). Motion and depth are data: only the channels they use (what read_data_image
    // reads), so a 1920x1080 frame's motion is 17 MB of floats and its depth 8 MB, not 33 MB each.
    // Full floats, not half: a replay gives the figures of the frames in memory exactly.
    static constexpr const char* kMotion[] = {"R", "G"};
    static constexpr const char* kDepth[] = {"Z"};
    for (std::size_t i = 0; i < source->frame_count(); ++i) {
        // `pick` gives the frame's image of that kind, or null where the frame has none.
        auto add = [&](const char* kind, std::span<const char* const> channels, auto pick) {
            const std::filesystem::path path = folder / frame_file(kind, i);
            writers.push_back({path, [cache, i, pick, path, channels](const std::filesystem::path& to) -> Result<void> {
                                   auto frame = cache->get(i);
                                   if (!frame) return std::unexpected(frame.error());
                                   const std::optional<Image> image = pick(**frame);
                                   if (!image)
                                       return fail(fmt::format("{}: frame {} of {} has none", path.string(), i,
                                                               cache->source->name()));
                                   return channels.empty() ? write_image_to(to, path.string(), *image)
                                                           : write_data_image_to(to, path.string(), *image, channels);
                               }});
        };
        add("color", {}, [](const LoadedFrame& f) { return std::optional<Image>(f.color); });
        if (!source->starts_history(i))
            add("motion", kMotion, [w, h](const LoadedFrame& f) {
                return f.motion.size() == std::size_t(w) * h ? std::optional(motion_image(f.motion, w, h))
                                                             : std::nullopt;
            });
        if (source->has_depth()) add("depth", kDepth, [](const LoadedFrame& f) { return f.depth; });
        if (source->has_reference()) add("reference", {}, [](const LoadedFrame& f) { return f.reference; });
    }
    return writers;
}

} // namespace kdop
