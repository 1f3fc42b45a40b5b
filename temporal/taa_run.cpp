#include "temporal/taa_run.h"

#include "bench/timing.h"
#include "core/shown_text.h"
#include "harness/gnuplot.h"
#include "harness/progress.h"
#include "harness/scratch_directory.h"
#include "harness/staged_images.h"
#include "harness/statistics.h"
#include "temporal/ghosting_picture.h"
#include "temporal/taa_chart.h"
#include "temporal/taa_report.h"

#include <fmt/format.h>

#include <iostream>
#include <set>

namespace kdop {

Result<RunMetadata> run_taa(const Context& context, const std::vector<VariantSpec>& specs,
                            std::span<const Variant* const> rectifiers, const TaaSources& sources,
                            const TaaRunSettings& settings, OutputSet& outputs) {
    const auto& [scenes, sequences] = sources;
    std::vector<VariantKey> keys;
    for (const VariantSpec& spec : specs) keys.push_back(spec.key());
    const TaaSchedule& schedule = settings.evaluation.schedule;
    auto evaluation = TaaEvaluation::create(context, specs, settings.evaluation);
    if (!evaluation) return std::unexpected(evaluation.error());

    // The rectification is timed at the frame size of what is measured: kdop's scenes', or, with
    // sequences only, the first sequence's.
    const std::uint32_t width = scenes.empty() ? sequences.front().width() : settings.width;
    const std::uint32_t height = scenes.empty() ? sequences.front().height() : settings.height;
    const HdrFlip picture_flip(settings.evaluation.ppd); // the pictures' FLIP maps
    StagedImages written_frames;
    EvaluationObserver observer;
    if (settings.write_frames)
        observer.output = [&](const std::string& sequence, std::size_t v, std::size_t index, const Image& output) {
            return written_frames.add(fmt::format("frames/{}/{}/{:04}.exr", sequence, keys[v].name(), index), output);
        };

    std::vector<TaaRow> rows;
    std::vector<std::string> pictures;
    {
        // Two lines, each with its own estimate: a timing round takes a fraction of a variant's TAA.
        Result<bench::TimingRun> timing;
        {
            Progress timing_progress(fmt::format("timing {} variants on {},", specs.size(), context.device_name()),
                                     settings.timing_rounds);
            timing =
                bench::time_interleaved(context, rectifiers, width, height, settings.timing_rounds, timing_progress);
            if (!timing) return std::unexpected(timing.error());
        }
        // A step is a frame, every variant resolved and measured on it.
        std::size_t frames = 0;
        for (const auto& scene : scenes) frames += evaluation->frames(*scene);
        for (const SequenceFrames& sequence : sequences) frames += sequence.frame_count();
        Progress progress(fmt::format("TAA of {} variants x {} scenes and sequences on {},", specs.size(),
                                      scenes.size() + sequences.size(), context.device_name()),
                          frames);
        observer.frame = [&](const std::string& source) { progress.advance(source); };
        std::set<std::string> warned; // HDR-FLIP's notes, once however many variants meet them
        auto add_rows = [&](const std::vector<EvaluationRow>& measured) {
            for (const EvaluationRow& m : measured) {
                const std::vector<double>& ms = timing->ms[m.variant];
                rows.push_back({keys[m.variant], m.source, median(ms), quantile(ms, 0.25), quantile(ms, 0.75),
                                m.shimmer, m.ghosting, m.against_reference ? "reference" : "aliased", m.range});
                for (const std::string& note : m.notes)
                    if (warned.insert(note).second) std::cerr << "warning: " << terminal_text(note) << "\n";
            }
        };
        for (const auto& scene : scenes) {
            auto measured = evaluation->measure(*scene, observer);
            if (!measured) return std::unexpected(measured.error());
            add_rows(*measured);
            auto shown = ghosting_frames(*scene, schedule)->frame(scene->trail_frame(schedule));
            if (!shown) return std::unexpected(shown.error());
            const bool has_reference = shown->reference.has_value();
            auto truth = std::make_shared<const Image>(std::move(has_reference ? *shown->reference : shown->color));
            std::vector<std::shared_ptr<const Image>> trails;
            std::vector<double> ghosting;
            for (const EvaluationRow& m : *measured) trails.push_back(m.trail), ghosting.push_back(m.ghosting);
            if (auto ok = add_ghosting_picture(outputs, *scene, has_reference ? "reference" : "aliased", truth, keys,
                                               trails, ghosting, picture_flip.ldr(), schedule);
                !ok)
                return std::unexpected(ok.error());
            pictures.push_back(ghosting_picture_name(scene->name()));
        }
        for (const SequenceFrames& sequence : sequences) {
            auto measured = evaluation->measure(sequence, observer);
            if (!measured) return std::unexpected(measured.error());
            add_rows(*measured);
        }
    }
    outputs.add(written_frames.writers(outputs.dir()));

    RunMetadata run_info = describe_run(context);
    run_info.seed = settings.seed;
    // A chart that fails costs the charts, not the run: the data, report and pictures are still written.
    std::vector<std::string> charts;
    if (charts_available(settings.charts)) {
        ScratchDirectory scratch("kdop-taa");
        auto drawn = scratch.path.empty() ? Result<std::vector<OutputFile>>(fail("no scratch directory"))
                                          : taa_charts(rows, scratch.path, outputs.dir());
        if (drawn) {
            outputs.add(std::move(*drawn));
            charts = taa_chart_names(rows);
        } else {
            warn_no_charts(drawn.error().message);
        }
    }
    std::vector<std::pair<std::string, std::string>> scene_contents;
    for (const auto& scene : scenes) scene_contents.emplace_back(scene->name(), scene->content());
    std::vector<std::string> sequence_names;
    for (const SequenceFrames& s : sequences) sequence_names.push_back(s.name());
    const EvaluationOptions& e = settings.evaluation;
    outputs.add_table("taa", taa_table(rows), run_info);
    outputs.add("report.md",
                taa_report_markdown(rows, run_info,
                                    {width, height, schedule.warmup, schedule.frames, e.ppd, pictures, charts,
                                     e.resolve, scene_contents, sequence_names, !e.cpu_flip, e.exposure}));
    if (auto ok = outputs.write(); !ok) return std::unexpected(ok.error());
    return run_info;
}

} // namespace kdop
