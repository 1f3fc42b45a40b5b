#include "temporal/taa_sources.h"

#include "core/input_files.h"
#include "temporal/taa_measure.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace kdop {

bool TaaSources::any_hdr() const {
    return std::ranges::any_of(sequences, [](const SequenceFrames& s) { return s.color_range() == ColorRange::hdr; });
}

Result<TaaSources> taa_sources(const Context& context, TaaSourceRequest request) {
    // Every size is checked against the device and memory before any frame is made or read.
    const SceneOptions& scene = request.scene_options;
    if (request.builtin)
        if (auto ok = check_measurable(context, scene.width, scene.height, request.device_flip, request.variants); !ok)
            return usage_fail(fmt::format("--size {}x{}: {}", scene.width, scene.height, ok.error().message));
    if (auto ok = check_distinct_files(request.sequences, request.option); !ok) return usage_fail(ok.error().message);
    TaaSources sources;
    for (const std::string& dir : request.sequences) {
        auto sequence = read_resolvable_sequence(dir, request.warmup, request.resolve);
        if (!sequence) return fail(sequence.error().message);
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
    if (request.builtin) {
        request.scene_options.context = &context;
        auto selected = select_taa_scenes(request.scene_names, request.backgrounds, request.scene_options);
        if (!selected) return fail(selected.error().message);
        sources.scenes = std::move(*selected);
    }
    std::set<std::string> names;
    for (const auto& s : sources.scenes) names.insert(s->name());
    for (const SequenceFrames& sequence : sources.sequences)
        if (!names.insert(sequence.name()).second)
            return fail(fmt::format("{}: {}: a scene or sequence is already called '{}'", request.option,
                                    sequence.sequence().dir.string(), sequence.name()));
    return sources;
}

} // namespace kdop
