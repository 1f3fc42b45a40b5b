#include "scenes/scene_export.h"

#include "harness/progress.h"
#include "sequence/nss_writer.h"
#include "sequence/sequence_writer.h"

#include <fmt/format.h>

#include <filesystem>
#include <string>

namespace kdop {

namespace {

// Every source as an NSS sequence, numbered in order, under outputs' folder: the JSON files added
// to `outputs`, the frames' writers returned. Refuses, before anything is drawn, a source NSS
// cannot hold.
Result<std::vector<OutputWriter>> nss_writers(const std::vector<std::shared_ptr<const FrameSource>>& sources,
                                              const SceneExportOptions& options, OutputSet& outputs) {
    std::vector<OutputWriter> writers;
    for (std::size_t s = 0; s < sources.size(); ++s) {
        const FrameSource& source = *sources[s];
        NssWriteOptions nss{.ratio = options.ratio, .precision = options.precision};
        // How the testbed jitters (Scene3dFrames::jitter): Halton (2, 3) when upscaling, else R2.
        nss.sample_sequence = options.ratio > 1 ? "Halton(2,3)" : source.jitter(0) ? "R2" : "None";
        if (auto ok = check_nss_writable(source, nss); !ok) {
            if (!source.has_reference())
                return usage_fail(fmt::format(
                    "--layout nss: {}; draw it with references: a 3-D scene (grass3d, asphalt3d) with "
                    "--reference-samples N, or --upscale R (16 reference samples by default); 2-D scenes have none",
                    ok.error().message));
            return std::unexpected(ok.error());
        }
        const std::string number = nss_sequence_number(s);
        outputs.add(number + ".json", nss_sequence_json(source, nss));
        for (OutputWriter& w : nss_frame_writers(outputs.dir(), number, sources[s], nss))
            writers.push_back(std::move(w));
    }
    outputs.add(kNssSequencesFile, nss_sequences_json(sources));
    return writers;
}

} // namespace

Result<std::vector<std::string>> export_scenes(const std::vector<std::shared_ptr<const TaaScene>>& scenes,
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
    std::vector<std::string> names;
    if (options.layout == SceneLayout::nss) {
        auto nss = nss_writers(sources, options, outputs);
        if (!nss) return std::unexpected(nss.error());
        writers = std::move(*nss);
    } else {
        for (const auto& source : sources) {
            outputs.add(source->name() + "/sequence.json", sequence_json(*source));
            for (OutputWriter& w : sequence_frame_writers(outputs.dir() / source->name(), source))
                writers.push_back(std::move(w));
        }
    }
    for (const auto& source : sources) names.push_back(source->name());
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
    return names;
}

} // namespace kdop
