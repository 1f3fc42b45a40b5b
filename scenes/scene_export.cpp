#include "scenes/scene_export.h"

#include "harness/progress.h"
#include "sequence/sequence_writer.h"

#include <fmt/format.h>

#include <filesystem>
#include <string>

namespace kdop {

Result<std::size_t> export_scenes(const std::vector<std::shared_ptr<const TaaScene>>& scenes,
                                  const SceneExportOptions& options, OutputSet& outputs) {
    std::vector<std::shared_ptr<const FrameSource>> sources;
    for (const auto& scene : scenes) {
        if (!options.animate && !options.jitter) {
            // kdop taa's own two: the schedule's frames split as warmup + the rest.
            const TaaSchedule schedule{0, options.frames};
            sources.push_back(shimmer_frames(*scene, schedule));
            sources.push_back(ghosting_frames(*scene, schedule));
        } else {
            sources.push_back(scene->frames(scene->name(), options.frames, options.animate.value_or(true),
                                            options.jitter.value_or(true)));
        }
    }
    std::vector<OutputWriter> writers;
    for (const auto& source : sources) {
        outputs.add(source->name() + "/sequence.json", sequence_json(*source));
        for (OutputWriter& w : sequence_frame_writers(outputs.dir() / source->name(), source))
            writers.push_back(std::move(w));
    }
    // The frames are drawn as they are written; the progress line follows the writes, a file each.
    Progress progress(fmt::format("Drawing and writing {} sequences:", sources.size()), writers.size());
    for (OutputWriter& w : writers)
        w.write = [&progress, inner = std::move(w.write),
                   name = w.path.lexically_relative(outputs.dir()).string()](const std::filesystem::path& temporary) {
            auto written = inner(temporary);
            if (written) progress.advance(name);
            return written;
        };
    outputs.add(std::move(writers));
    if (auto ok = outputs.write(); !ok) return fail(ok.error().message);
    return sources.size();
}

} // namespace kdop
