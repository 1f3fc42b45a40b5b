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
#include "temporal/taa_intervals.h"
#include "temporal/taa_ranks.h"
#include "temporal/taa_report.h"
#include "temporal/taa_report_page.h"
#include "temporal/taa_shader.h"
#include "temporal/viewer_frames.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <optional>
#include <set>

namespace kdop {
namespace {

// Whether any source's frames are smaller than its outputs.
bool upscales(const TaaSources& sources, const TaaSchedule& schedule) {
    return std::ranges::any_of(sources.sequences, &FrameSource::upscales) ||
           std::ranges::any_of(sources.captures, &FrameSource::upscales) ||
           std::ranges::any_of(sources.scenes,
                               [&](const auto& scene) { return shimmer_frames(*scene, schedule)->upscales(); });
}

// The keys of the rows `measured` holds: the variants', and the spatial-only upscale's where it is
// among them.
std::vector<VariantKey> keys_of(const std::vector<VariantKey>& keys, const std::vector<EvaluationRow>& measured) {
    return {keys.begin(), keys.begin() + std::ptrdiff_t(std::min(keys.size(), measured.size()))};
}

// taa.csv's row of variant `key` on `m.source`, timed by `ms`: each metric's figures summarized
// over its frames (the mean as measured).
TaaRow taa_row(const VariantKey& key, const EvaluationRow& m, const std::vector<double>& ms, const Metrics& metrics) {
    TaaRow row;
    row.key = key, row.scene = m.source;
    row.ms = median(ms), row.ms_q1 = quantile(ms, 0.25), row.ms_q3 = quantile(ms, 0.75);
    for (std::size_t metric = 0; metric < metrics.size(); ++metric) {
        const MetricSummary summary = summarize(m.per_frame, metric, metrics[metric].higher_is_better);
        MetricFigures& f = row.figures.emplace_back();
        f.mean = m.mean(metric), f.median = summary.median, f.p95 = summary.p95;
        if (summary.worst)
            f.worst_frame =
                fmt::format("{} frame {}", m.per_frame[*summary.worst].sequence, m.per_frame[*summary.worst].index);
    }
    row.truth = m.against_reference ? "reference" : "aliased";
    row.range = m.range;
    row.upscale = m.upscale;
    return row;
}

// A sequence's ghosting picture at the frame `chooser` kept, cropped where the variants differ most.
// `sequence` is the source as the pass read it (a sequence's without its depth files).
Result<void> add_sequence_picture(StagedImages& outputs, const FrameSource& sequence,
                                  const PictureFrameChooser& chooser, const std::vector<VariantKey>& keys,
                                  const std::vector<EvaluationRow>& measured, PictureFlip& flip) {
    auto frame = sequence.frame(chooser.index()); // its truth, as the pass read it
    if (!frame) return std::unexpected(frame.error());
    const bool has_reference = frame->reference.has_value();
    auto truth = std::make_shared<const Image>(std::move(has_reference ? *frame->reference : frame->color));
    auto maps = ghosting_maps(flip, *truth, chooser.outputs());
    if (!maps) return fail(fmt::format("{}: {}", sequence.frame_label(chooser.index()), maps.error().message));
    std::vector<double> ghosting;
    for (const EvaluationRow& m : measured) ghosting.push_back(m.mean(kGhosting));
    const PictureFrame shown{sequence.name(), chooser.index(),
                             disagreement_crop(*maps, sequence.width(), sequence.height())};
    return add_ghosting_picture(outputs, shown, has_reference ? "reference" : "aliased", truth, keys, chooser.outputs(),
                                *maps, ghosting, flip);
}

// A scene's ghosting picture: every variant's trail frame over its FLIP map against the truth.
Result<void> add_scene_picture(StagedImages& outputs, const TaaScene& scene, const TaaSchedule& schedule,
                               const std::vector<VariantKey>& keys, const std::vector<EvaluationRow>& measured,
                               TaaEvaluation& evaluation) {
    auto shown = ghosting_frames(scene, schedule)->frame(scene.trail_frame(schedule));
    if (!shown) return std::unexpected(shown.error());
    const bool has_reference = shown->reference.has_value();
    auto truth = std::make_shared<const Image>(std::move(has_reference ? *shown->reference : shown->color));
    std::vector<std::shared_ptr<const Image>> held;
    std::vector<double> ghosting;
    for (const EvaluationRow& m : measured) held.push_back(m.trail), ghosting.push_back(m.mean(kGhosting));
    const PictureFrames trails = frames_in_memory(std::move(held));
    const PictureFrame at{scene.name(), scene.trail_frame(schedule), scene.trail_crop(schedule)};
    auto flip = evaluation.flip_evaluator(truth->width, truth->height);
    if (!flip) return std::unexpected(flip.error());
    PictureFlip picture_flip(**flip, ColorRange::ldr);
    auto maps = ghosting_maps(picture_flip, *truth, trails);
    if (!maps) return std::unexpected(maps.error());
    return add_ghosting_picture(outputs, at, has_reference ? "reference" : "aliased", truth, keys, trails, *maps,
                                ghosting, picture_flip);
}

// The viewer's frames of every sequence measured, planned before the pass, each with the
// evaluation's shaders for it (the spatial-only upscale only where it upscales).
void plan_viewer(ViewerFrames& viewer, const TaaSources& sources, const TaaSchedule& schedule,
                 const TaaEvaluation& evaluation, const std::function<bool(std::size_t)>& mine) {
    const std::size_t last = schedule.warmup + schedule.frames - 1;
    for (std::size_t i = 0; i < sources.scenes.size(); ++i) {
        if (!mine(i)) continue;
        const TaaScene& scene = *sources.scenes[i];
        const auto still = shimmer_frames(scene, schedule), moving = ghosting_frames(scene, schedule);
        for (const FrameSource* frames : {still.get(), moving.get()})
            viewer.plan(frames->name(), scene.name(), schedule.warmup, last, frames->roles(), frames->color_range(),
                        frames->has_reference(), evaluation.shader_count(*frames));
    }
    auto plan = [&](const FrameSource& source) {
        viewer.plan(source.name(), source.name(), schedule.warmup, source.frame_count() - 1, source.roles(),
                    source.color_range(), source.has_reference(), evaluation.shader_count(source));
    };
    std::size_t i = sources.scenes.size();
    for (const SequenceFrames& sequence : sources.sequences)
        if (mine(i++)) plan(sequence);
    for (const NssFrames& capture : sources.captures)
        if (mine(i++)) plan(capture);
}

// The trade and over-time charts, added to `outputs` with their names. A chart that fails costs the
// charts, not the run: the data, report and pictures are still written.
void add_charts(OutputSet& outputs, const std::vector<TaaRow>& rows, const std::vector<TaaFrameRow>& frame_rows,
                const Metrics& metrics, std::vector<std::string>& charts, std::vector<std::string>& over_time_charts) {
    ScratchDirectory scratch("kdop-taa");
    auto drawn = scratch.path.empty() ? Result<std::vector<OutputFile>>(fail("no scratch directory"))
                                      : taa_charts(rows, metrics, scratch.path, outputs.dir());
    auto over_time = drawn ? taa_over_time_charts(frame_rows, metrics, scratch.path, outputs.dir()) : drawn;
    if (!drawn || !over_time) return warn_no_charts((drawn ? over_time : drawn).error().message);
    outputs.add(std::move(*drawn));
    outputs.add(std::move(*over_time));
    charts = taa_chart_names(rows);
    over_time_charts = taa_over_time_chart_names(frame_rows);
}

// What report.md and report.html say of the run, but for its pictures and charts.
TaaReportSettings report_settings(const TaaSources& sources, const TaaRunSettings& settings, std::uint32_t width,
                                  std::uint32_t height) {
    std::vector<std::pair<std::string, std::string>> scene_contents;
    for (const auto& scene : sources.scenes) scene_contents.emplace_back(scene->name(), scene->content());
    std::vector<std::string> sequence_names;
    for (const SequenceFrames& s : sources.sequences) sequence_names.push_back(s.name());
    for (const NssFrames& c : sources.captures) sequence_names.push_back(c.name());
    const EvaluationOptions& e = settings.evaluation;
    // The resolve as the report describes it: upscaling where any source's frames are smaller
    // than its output (the evaluation sets it per source).
    ResolveOptions resolve = e.resolve;
    resolve.upscale = upscales(sources, e.schedule);
    return {.width = width,
            .height = height,
            .warmup = e.schedule.warmup,
            .frames = e.schedule.frames,
            .pixels_per_degree = e.ppd,
            .pictures = {},
            .charts = {},
            .over_time = {},
            .resolve = resolve,
            .own_resolve = e.own_resolve ? e.own_resolve->label() : std::string(),
            .scene_contents = std::move(scene_contents),
            .sequences = std::move(sequence_names),
            .flip_on_device = !e.cpu_flip,
            .hdr = e.exposure,
            .metrics = e.metrics};
}

// The frame size the rectification is timed at, that of what is measured: kdop's scenes', or,
// with sequences only, the first sequence's (or NSS capture's): the output size where it upscales.
std::pair<std::uint32_t, std::uint32_t> timing_size(const TaaSources& sources, const TaaRunSettings& settings) {
    const FrameSource* first = !sources.scenes.empty() ? nullptr
                               : !sources.sequences.empty()
                                   ? static_cast<const FrameSource*>(&sources.sequences.front())
                                   : &sources.captures.front();
    return first ? std::pair(first->width(), first->height()) : std::pair(settings.width, settings.height);
}

// The frames a run goes through: what its progress counts.
std::size_t frame_steps(const TaaEvaluation& evaluation, const TaaSources& sources) {
    std::size_t frames = 0;
    for (const auto& scene : sources.scenes) frames += evaluation.frames(*scene);
    for (const SequenceFrames& sequence : sources.sequences) frames += sequence.frame_count();
    for (const NssFrames& capture : sources.captures) frames += capture.frame_count();
    return frames;
}

// `shares` with what each rank measured, as the run's metadata says.
std::vector<RunMetadata::RankShare> rank_shares(const TaaSources& sources, const std::vector<int>& owners,
                                                std::vector<RunMetadata::RankShare> shares) {
    std::vector<std::string> names;
    for (const auto& scene : sources.scenes) names.push_back(scene->name());
    for (const SequenceFrames& sequence : sources.sequences) names.push_back(sequence.name());
    for (const NssFrames& capture : sources.captures) names.push_back(capture.name());
    for (std::size_t i = 0; i < owners.size(); ++i) shares[std::size_t(owners[i])].measured.push_back(names[i]);
    return shares;
}

// The charts, the intervals, taa.csv, taa_frames.csv, report.md and report.html of what a run
// measured, and every output staged, written.
Result<RunMetadata> write_tables_and_reports(RunMetadata run_info, const TaaRunSettings& settings,
                                             TaaReportSettings& report, std::vector<TaaRow>& rows,
                                             const std::vector<TaaFrameRow>& frame_rows,
                                             const std::vector<std::string>& variant_names,
                                             const std::vector<ViewerSequence>& viewed, OutputSet& outputs) {
    const Metrics& metrics = settings.evaluation.metrics;
    run_info.seed = settings.seed;
    if (settings.evaluation.own_resolve) run_info.resolve = settings.evaluation.own_resolve->label();
    if (charts_available(settings.charts))
        add_charts(outputs, rows, frame_rows, metrics, report.charts, report.over_time);
    BootstrapOptions bootstrap;
    bootstrap.block = history_block(settings.evaluation.resolve.current_weight), bootstrap.seed = settings.seed;
    add_intervals(rows, frame_rows, metrics.size(), bootstrap);
    outputs.add_table("taa", taa_table(rows, metrics), run_info);
    outputs.add_table("taa_frames", taa_frames_table(frame_rows, metrics), run_info);
    outputs.add("report.md", taa_report_markdown(rows, run_info, report));
    outputs.add("report.html", taa_report_html(rows, run_info, report, variant_names, viewed));
    if (auto ok = outputs.write(); !ok) return std::unexpected(ok.error());
    return run_info;
}

} // namespace

Result<RunMetadata> run_taa(const Context& context, const std::vector<VariantSpec>& specs,
                            std::span<const Variant* const> rectifiers, const TaaSources& sources,
                            const TaaRunSettings& settings, OutputSet& outputs, const Ranks& ranks) {
    const auto& [scenes, sequences, captures] = sources;
    std::vector<VariantKey> keys;
    for (const VariantSpec& spec : specs) keys.push_back(spec.key());
    const TaaSchedule& schedule = settings.evaluation.schedule;
    const Metrics& metrics = settings.evaluation.metrics;
    auto evaluation = TaaEvaluation::create(context, specs, settings.evaluation);
    if (auto ok = ranks.agree(evaluation ? Result<void>{} : std::unexpected(evaluation.error())); !ok)
        return std::unexpected(ok.error());
    // The spatial-only upscale's rows, last, where a source upscales (EvaluationOptions::spatial_upscale).
    if (settings.evaluation.spatial_upscale && upscales(sources, schedule) && !settings.evaluation.own_resolve)
        keys.push_back({spatial_upscale_name(settings.evaluation.resolve.upscale_filter), Mode::shader});
    std::vector<std::string> variant_names;
    for (const VariantKey& key : keys) variant_names.push_back(key.name());

    // This rank's sources (taa_ranks.h): all of them on one.
    const std::vector<int> owners = source_owners(ranks, sources, *evaluation, schedule);
    auto mine = [&](std::size_t i) { return owners[i] == ranks.rank(); };
    // Every image the run writes, staged as it is made: the pictures, the viewer's frames and
    // --write-frames' outputs.
    StagedImages images;
    EvaluationObserver observer;
    if (settings.write_frames)
        observer.output = [&](const std::string& sequence, std::size_t v, std::size_t index, const Image& output) {
            return images.add(fmt::format("frames/{}/{}/{:04}.exr", sequence, keys[v].name(), index), output);
        };
    ViewerFrames viewer(settings.viewer_frames, variant_names, images, settings.evaluation.exposure);
    if (settings.viewer_frames > 0) {
        plan_viewer(viewer, sources, schedule, *evaluation, mine);
        observer.measured = [&](const MeasuredFrame& frame) { return viewer.offer(frame); };
        observer.maps = true; // the viewer shows the maps the figures were measured with
    }

    const auto [width, height] = timing_size(sources, settings);
    std::optional<bench::TimingRun> timing; // rank 0's, of every variant
    std::vector<std::optional<MeasuredSource>> measured(sources.size());
    // Rank 0's one progress line counts every rank's frames: the others tell it theirs.
    std::optional<Progress> progress;
    bool stopped = false; // by rank 0, another rank having failed
    auto measure_mine = [&]() -> Result<void> {
        if (ranks.is_root()) {
            // Two lines, each with its own estimate: a timing round takes a fraction of a variant's TAA.
            Progress timing_progress(fmt::format("timing {} variants on {},", specs.size(), context.device_name()),
                                     settings.timing_rounds);
            auto timed =
                bench::time_interleaved(context, rectifiers, width, height, settings.timing_rounds, timing_progress);
            if (!timed) return std::unexpected(timed.error());
            timing = std::move(*timed);
        }
        // A step is a frame, every variant resolved and measured on it, on any rank.
        std::size_t count = 0;
        for (std::size_t i = 0; i < sources.size(); ++i) count += mine(i);
        progress.emplace(fmt::format("TAA of {} variants x {} scenes and sequences on {}{},", specs.size(),
                                     sources.size(), context.device_name(),
                                     ranks.size() == 1 ? std::string() : fmt::format(" and {} ranks", ranks.size())),
                         frame_steps(*evaluation, sources), "frames");
        // Each line says which source of how many, for a corpus of hundreds.
        std::vector<std::string> started;
        observer.frame = [&](const std::string& source) -> Result<void> {
            if (started.empty() || started.back() != source) started.push_back(source);
            const std::string item = ranks.size() == 1
                                         ? fmt::format("{} ({} of {})", source, started.size(), count)
                                         : fmt::format("{} ({} of {} on rank 0)", source, started.size(), count);
            progress->advance(item);
            progress->advance(item, ranks.take_progress());
            ranks.tell_progress(1);
            // Another rank failed: its error will be everyone's, and the rest of this share is of no use.
            if (ranks.stop_asked()) {
                stopped = true;
                return fail("stopped: another rank failed");
            }
            return {};
        };
        for (std::size_t i = 0; i < scenes.size(); ++i) {
            if (!mine(i)) continue;
            const TaaScene& scene = *scenes[i];
            viewer.measuring(scene.name());
            auto rows = evaluation->measure(scene, observer);
            if (!rows) return std::unexpected(rows.error());
            if (auto ok = add_scene_picture(images, scene, schedule, keys_of(keys, *rows), *rows, *evaluation); !ok)
                return std::unexpected(ok.error());
            for (EvaluationRow& row : *rows) row.trail.reset(); // pictured: a frame per variant let go
            measured[i] =
                MeasuredSource{.rows = std::move(*rows), .picture = ghosting_picture_name(scene.name()), .viewed = {}};
        }
        // A sequence or NSS capture: `read` is the source as the pass reads it, `measure` its measurement.
        auto measure_sequence = [&](std::size_t i, const FrameSource& read, const auto& measure) -> Result<void> {
            // The frame its picture shows, kept as the pass goes (sequences meant for ghosting).
            PictureFrameChooser chooser(settings.picture_frame);
            const bool pictured = read.roles().ghosting;
            EvaluationObserver sequence_observer = observer;
            if (pictured)
                sequence_observer.measured = [&](const MeasuredFrame& frame) -> Result<void> {
                    if (auto ok = chooser.offer(frame); !ok) return ok;
                    return observer.measured ? observer.measured(frame) : Result<void>{};
                };
            viewer.measuring(read.name());
            auto rows = measure(sequence_observer);
            if (!rows) return std::unexpected(rows.error());
            MeasuredSource source{.rows = std::move(*rows), .picture = {}, .viewed = {}};
            if (pictured && chooser.chosen()) {
                auto evaluator = evaluation->flip_evaluator(read.width(), read.height());
                if (!evaluator) return std::unexpected(evaluator.error());
                PictureFlip flip(**evaluator, read.color_range());
                if (auto ok =
                        add_sequence_picture(images, read, chooser, keys_of(keys, source.rows), source.rows, flip);
                    !ok)
                    return std::unexpected(ok.error());
                source.picture = ghosting_picture_name(read.name());
            }
            measured[i] = std::move(source);
            return {};
        };
        for (std::size_t s = 0; s < sequences.size(); ++s)
            if (const std::size_t i = scenes.size() + s; mine(i))
                if (auto ok = measure_sequence(
                        i, sequences[s].without_depth(),
                        [&](const EvaluationObserver& o) { return evaluation->measure(sequences[s], o); });
                    !ok)
                    return ok;
        for (std::size_t c = 0; c < captures.size(); ++c)
            if (const std::size_t i = scenes.size() + sequences.size() + c; mine(i))
                if (auto ok = measure_sequence(
                        i, captures[c],
                        [&](const EvaluationObserver& o) { return evaluation->measure(captures[c], false, o); });
                    !ok)
                    return ok;
        return {};
    };
    // The viewer's staged frames written, and what it shows of each source handed to its measurement.
    auto write_viewer = [&]() -> Result<void> {
        Progress progress("Writing report.html's worst frames and FLIP maps:", viewer.staged_frames());
        auto viewed = viewer.write([&](const std::string& sequence) { progress.advance(sequence); });
        if (!viewed) return std::unexpected(viewed.error());
        auto next = viewed->begin();
        for (std::size_t i = 0; i < sources.size() && next != viewed->end(); ++i)
            if (mine(i))
                for (std::size_t k = 0; k < viewed_sequences(sources, i); ++k) measured[i]->viewed.push_back(*next++);
        return {};
    };
    // This rank's own time: its share and its viewer's frames, not the waits for the others.
    auto started = std::chrono::steady_clock::now();
    Result<void> done = measure_mine();
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    // Every rank says it is done, well or not, and rank 0 counts the others' frames until they are,
    // stopping them all where one failed.
    const bool failed = !done && !stopped;
    if (ranks.is_root())
        ranks.wait_for_progress(
            [&](std::size_t steps) {
                if (progress) progress->advance("the other ranks' sources", steps);
            },
            !failed);
    else
        ranks.finish_progress(!failed);
    progress.reset();
    if (done && settings.viewer_frames > 0) {
        started = std::chrono::steady_clock::now();
        done = write_viewer();
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    }
    // A rank that failed stops them all, with its message, before anything is gathered or written. A
    // rank told to stop gives its success, so that the failing rank's error is everyone's.
    if (auto ok = ranks.agree(stopped ? Result<void>{} : std::move(done)); !ok) return std::unexpected(ok.error());
    if (ranks.size() > 1) std::cerr << "Gathering the figures and images of " << ranks.size() << " ranks\n";
    const RunMetadata::RankShare me{context.device_name(), seconds, {}};
    GatheredSources gathered = gather_sources(ranks, std::move(measured), me, images);
    if (!ranks.is_root()) return describe_run(context);

    std::vector<TaaRow> rows;
    std::vector<TaaFrameRow> frame_rows;
    std::vector<std::string> pictures;
    std::vector<ViewerSequence> viewed;
    std::set<std::string> warned; // HDR-FLIP's notes, once however many variants meet them
    for (MeasuredSource& source : gathered.sources) {
        for (const EvaluationRow& m : source.rows) {
            // The spatial-only upscale has no rectification to time.
            const std::vector<double> none;
            const std::vector<double>& ms = m.variant < timing->ms.size() ? timing->ms[m.variant] : none;
            rows.push_back(taa_row(keys[m.variant], m, ms, metrics));
            for (const FrameFigures& f : m.per_frame)
                frame_rows.push_back({keys[m.variant], m.source, f.sequence, f.index, f.values, m.range});
            for (const std::string& note : m.notes)
                if (warned.insert(note).second) std::cerr << "warning: " << terminal_text(note) << "\n";
        }
        if (!source.picture.empty()) pictures.push_back(source.picture);
        for (ViewerSequence& sequence : source.viewed) viewed.push_back(std::move(sequence));
    }
    outputs.add(images.writers(outputs.dir()));

    TaaReportSettings report = report_settings(sources, settings, width, height);
    report.pictures = pictures;
    RunMetadata run_info = describe_run(context);
    if (ranks.size() > 1) run_info.ranks = rank_shares(sources, owners, std::move(gathered.shares));
    return write_tables_and_reports(std::move(run_info), settings, report, rows, frame_rows, variant_names, viewed,
                                    outputs);
}

} // namespace kdop
