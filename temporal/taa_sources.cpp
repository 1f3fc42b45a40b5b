#include "temporal/taa_sources.h"

#include "core/input_files.h"
#include "sequence/sequence_corpus.h"
#include "temporal/taa_measure.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace kdop {

bool TaaSources::any_hdr() const {
    return std::ranges::any_of(captures, [](const NssFrames& c) { return c.color_range() == ColorRange::hdr; }) ||
           std::ranges::any_of(sequences, [](const SequenceFrames& s) { return s.color_range() == ColorRange::hdr; });
}

namespace {

// NSS sequence `name` of the capture root `dir`, read and checked, added to `sources`.
Result<void> add_nss_capture(const Context& context, const TaaSourceRequest& request, const std::string& dir,
                             const std::string& name, TaaSources& sources) {
    auto capture = read_nss_capture(dir, name, request.nss_ratio);
    if (!capture) return std::unexpected(capture.error());
    const std::size_t count = capture->frames.size();
    if (request.warmup >= count)
        return usage_fail(fmt::format("{} {} --nss-sequence {}: {} frames, and --warmup {} leaves none to measure; "
                                      "give a shorter warm-up, e.g. --warmup {} (a third of the frames)",
                                      request.option, dir, name, count, request.warmup,
                                      std::max<std::size_t>(1, count / 3)));
    if (auto ok = check_measurable(context, capture->width, capture->height, request.device_flip, request.variants);
        !ok)
        return fail(fmt::format("{} {}: {}", request.option, dir, ok.error().message));
    if (request.picture_frame && (*request.picture_frame < request.warmup || *request.picture_frame >= count))
        return usage_fail(fmt::format("--picture-frame {}: not a measured frame of --nss-sequence {} (frames {} to "
                                      "{}, after the warmup)",
                                      *request.picture_frame, name, request.warmup, count - 1));
    // Depth is read only where the resolve reads it (--dilate-motion, a renderer's depth role).
    NssFrames frames(std::move(*capture), request.nss_range);
    const bool depth = request.resolve.dilate_motion || request.own_reads_depth;
    sources.captures.push_back(depth ? std::move(frames) : frames.without_depth());
    return {};
}

} // namespace

Result<TaaSources> taa_sources(const Context& context, TaaSourceRequest request) {
    // Every size is checked against the device and memory before any frame is made or read.
    const SceneOptions& scene = request.scene_options;
    if (request.builtin)
        if (auto ok = check_measurable(context, scene.width, scene.height, request.device_flip, request.variants); !ok)
            return usage_fail(fmt::format("--size {}x{}: {}", scene.width, scene.height, ok.error().message));
    if (auto ok = check_distinct_files(request.sequences, request.option); !ok) return usage_fail(ok.error().message);
    TaaSources sources;
    for (const std::string& dir : request.nss_sequence.empty() ? std::vector<std::string>{} : request.sequences) {
        // --nss-sequence all: every sequence of the root, in numeric order.
        auto names = request.nss_sequence == "all"
                         ? nss_sequences(dir)
                         : Result<std::vector<std::string>>(std::vector{request.nss_sequence});
        if (!names)
            return fail(fmt::format("{} {} --nss-sequence all: {}", request.option, dir, names.error().message));
        for (const std::string& name : *names)
            if (auto ok = add_nss_capture(context, request, dir, name, sources); !ok)
                return std::unexpected(ok.error());
    }
    for (const std::string& dir : request.nss_sequence.empty() ? request.sequences : std::vector<std::string>{}) {
        auto sequence = read_resolvable_sequence(dir, request.warmup, request.resolve, request.option);
        if (!sequence) return std::unexpected(sequence.error());
        if (auto ok =
                check_measurable(context, sequence->width, sequence->height, request.device_flip, request.variants);
            !ok)
            return fail(fmt::format("{} {}: {}", request.option, dir, ok.error().message));
        if (request.picture_frame && sequence->measure.ghosting &&
            (*request.picture_frame < request.warmup || *request.picture_frame >= sequence->frames.size()))
            return usage_fail(fmt::format("--picture-frame {}: not a measured frame of --sequence {} (frames {} to {}, "
                                          "after the warmup)",
                                          *request.picture_frame, dir, request.warmup, sequence->frames.size() - 1));
        sources.sequences.emplace_back(std::move(*sequence), request.input_space);
    }
    // --picture-frame picks the frame of a sequence's ghosting picture: kdop's scenes show their
    // trail's frame, and a sequence meant for shimmer alone has no such picture.
    if (request.picture_frame && sources.captures.empty() &&
        std::ranges::none_of(sources.sequences, [](const SequenceFrames& s) { return s.sequence().measure.ghosting; }))
        return usage_fail(fmt::format("--picture-frame {}: picks the frame of each --sequence's ghosting picture, "
                                      "and no sequence given is measured for ghosting (kdop's own scenes show the "
                                      "frame of their trail)",
                                      *request.picture_frame));
    if (request.builtin) {
        request.scene_options.context = &context;
        auto selected = select_taa_scenes(request.scene_names, request.backgrounds, request.scene_options);
        if (!selected) return std::unexpected(selected.error());
        sources.scenes = std::move(*selected);
    }
    // Rows and charts are named after each scene and sequence, frames and pictures after each
    // sequence, a scene's two included (<scene>-shimmer, <scene>-ghosting): every one of those names
    // must be distinct, or one source's files would replace another's.
    std::set<std::string> names;
    for (const auto& scene : sources.scenes)
        for (const std::string& name : {scene->name(), scene->name() + "-shimmer", scene->name() + "-ghosting"})
            if (!names.insert(name).second)
                return usage_fail(fmt::format("--background: the scene '{}' would write its files as '{}', which "
                                              "another scene's files are named; rename the image",
                                              scene->name(), name));
    for (const NssFrames& capture : sources.captures)
        if (!names.insert(capture.name()).second)
            return usage_fail(fmt::format("--nss-sequence {}: its files would be named '{}', as a scene's are",
                                          capture.name(), capture.name()));
    for (const SequenceFrames& sequence : sources.sequences)
        if (!names.insert(sequence.name()).second)
            return usage_fail(fmt::format("{} {}: its files would be named '{}', as a scene's or another "
                                          "sequence's are (a scene's frames are <scene>-shimmer and "
                                          "<scene>-ghosting); rename the folder",
                                          request.option, sequence.sequence().dir.string(), sequence.name()));
    return sources;
}

} // namespace kdop
