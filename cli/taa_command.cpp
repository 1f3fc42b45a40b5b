#include "commands.h"

#include "command_line.h"
#include "device_flip.h"
#include "flip.h"
#include "gnuplot.h"
#include "hdr_flip_option.h"
#include "image_io.h"
#include "input_files.h"
#include "input_space_option.h"
#include "magma.h"
#include "number_option.h"
#include "output_set.h"
#include "progress.h"
#include "resolve_option.h"
#include "run_metadata.h"
#include "scene_options.h"
#include "scratch_directory.h"
#include "selection_options.h"
#include "sequence.h"
#include "shown_text.h"
#include "size_option.h"
#include "staged_images.h"
#include "statistics.h"
#include "taa_chart.h"
#include "taa_measure.h"
#include "taa_report.h"
#include "taa_resolve.h"
#include "taa_shader.h"
#include "timing.h"
#include "trail_picture.h"
#include "variant_catalog.h"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <set>

namespace kdop::cli {
namespace {

// ghosting-<scene>.png
std::string trail_picture_name(const std::string& scene) { return fmt::format("ghosting-{}.png", scene); }

// What a scene shows of its ghosting, added to `outputs`: the truth (the aliased frame, or the
// reference where the scene has one) and each variant's frame at the trail frame under
// frames/<scene>/, as data (EXR) and to look at (PNG), and the labeled picture of them all, each
// variant's crop over its FLIP map against the truth, under it the variant's ghosting (the mean
// over the measured frames) and this frame's mean FLIP, and the maps' color scale under the grid.
Result<void> add_trail_outputs(OutputSet& outputs, const TaaScene& scene, const std::string& truth_name,
                               std::shared_ptr<const Image> truth, const std::vector<VariantKey>& keys,
                               const std::vector<std::shared_ptr<const Image>>& trails,
                               const std::vector<double>& ghosting, const LdrFlip& flip, const TaaSchedule& schedule) {
    const std::uint32_t width = truth->width, height = truth->height;
    std::vector<std::pair<std::string, std::shared_ptr<const Image>>> frames{{truth_name, truth}};
    std::vector<Image> maps;
    maps.reserve(trails.size()); // the picture points into it
    std::vector<LabeledFrame> labeled{
        {fmt::format("{}, frame {}", truth_name, scene.trail_frame(schedule)), truth.get()}};
    for (std::size_t v = 0; v < keys.size(); ++v) {
        auto error = flip.error_map(*truth, *trails[v]);
        if (!error) return std::unexpected(error.error());
        maps.push_back(flip::magma_image(*error, width, height));
        frames.emplace_back(keys[v].name(), trails[v]);
        labeled.push_back({keys[v].name(), trails[v].get(), &maps.back(),
                           fmt::format("ghosting {:.4f} | frame {:.4f}", ghosting[v], mean_error(*error))});
    }
    std::vector<float> ramp(256);
    for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = float(i) / float(ramp.size() - 1);
    const Image bar = flip::magma_image(ramp, std::uint32_t(ramp.size()), 1);
    const std::string caption = "LDR-FLIP against the " + (truth_name == "aliased" ? "aliased frame" : truth_name);
    const ColorScale scale{&bar, caption};
    for (const auto& [stem, image] : frames)
        for (const char* extension : {".exr", ".png"})
            outputs.add_image(fmt::format("frames/{}/{}{}", scene.name(), stem, extension), image);
    auto picture = trail_picture(labeled, scene.trail_crop(schedule), 4, &scale);
    if (!picture) return std::unexpected(picture.error());
    outputs.add_image(trail_picture_name(scene.name()), std::make_shared<const Image>(std::move(*picture)));
    return {};
}

std::vector<std::string> sequence_names(const std::vector<SequenceFrames>& sequences) {
    std::vector<std::string> names;
    for (const SequenceFrames& s : sequences) names.push_back(s.name());
    return names;
}

} // namespace

Action add_taa_command(CLI::App& app) {
    struct Options {
        std::string out, size = "320x180", device;
        std::vector<std::string> sequences;
        SceneChoice choice;
        SelectionOptions selection;
        std::uint32_t warmup = 100, frames = 100;
        unsigned timing_rounds = 15;
        std::uint64_t seed = 1;
        double ppd = 0;
        bool validation = false, no_charts = false, write_frames = false, cpu_flip = false;
        InputSpace input_space = InputSpace::from_file;
        ResolveOptions resolve;
        ExposureOptions exposure; // HDR-FLIP's, for HDR sequences
    };
    auto o = std::make_shared<Options>();
    CLI::App* taa = app.add_subcommand(
        "taa", "Run every variant in one TAA resolve on the device over kdop's scenes or your own frame sequences "
               "and measure the ghosting and shimmer a viewer sees, in LDR-FLIP (HDR sequences in HDR-FLIP), as Ikkala "
               "et al. 2024 do (Tables 1 and 2); writes taa.csv (and JSON), report.md, selected frames as EXR and PNG "
               "and one labeled ghosting "
               "picture per built-in scene");
    taa->add_option("--out", o->out, "Output directory (created if missing)")->required();
    o->selection.add_to(*taa, true, "n9, the paper's rows");
    o->choice.add_to(*taa);
    taa->add_option("--sequence", o->sequences,
                    "Frame sequences to measure (folders with sequence.json; README \"Frame sequences\"); with "
                    "--sequence, kdop's own scenes run only if --scenes or --background is given too");
    add_input_space_option(*taa, o->input_space);
    add_resolve_options(*taa, o->resolve);
    taa->add_flag("--write-frames", o->write_frames,
                  "Also write every measured output as EXR, frames/<sequence>/<variant>/NNNN.exr (kdop's scenes: "
                  "<scene>-shimmer and <scene>-ghosting)");
    taa->add_option("--size", o->size, "Frame size WIDTHxHEIGHT [default: 320x180]");
    taa->add_option("--warmup", o->warmup, "Frames before measuring, in every sequence [default: 100]")
        ->check(whole_number(1, 100000));
    taa->add_option("--frames", o->frames,
                    "Frames measured in kdop's scenes (a sequence: all after the warmup) [default: 100]")
        ->check(whole_number(1, 100000));
    taa->add_option("--ppd", o->ppd,
                    "FLIP's pixels per degree [default: 0.7 m from a 0.7 m wide 3840-pixel display, about 67]")
        ->check(finite_number(kMinPixelsPerDegree, kMaxPixelsPerDegree));
    taa->add_option("--timing-rounds", o->timing_rounds, "Interleaved dispatches per variant for ms [default: 15]")
        ->check(whole_number(1, 10000));
    taa->add_option("--seed", o->seed, "Seed of the synthetic textures and the 3-D scenes [default: 1]")
        ->check(seed_number());
    taa->add_option("--device", o->device,
                    "Vulkan device: a substring of its name [default: $KDOP_DEVICE, else lavapipe]");
    taa->add_flag("--validation", o->validation, "Enable the Khronos validation layer (slower)");
    taa->add_flag("--cpu-flip", o->cpu_flip,
                  "Measure ghosting and shimmer with the CPU's FLIP, the reference code the device's is tested "
                  "against, instead of on the device");
    // HDR sequences ("color": {"range": "hdr"}) are measured in HDR-FLIP at these.
    const std::vector<CLI::Option*> hdr_options = add_hdr_flip_options(*taa, o->exposure);
    taa->add_flag("--no-charts", o->no_charts, "Write the tables, report and pictures without the trade charts");

    return [o, taa, hdr_options] {
        if (o->selection.baselines)
            return report_error("--baselines: the gather and copy baselines are not clips; they have no place in TAA");
        const double ppd = taa->count("--ppd") ? o->ppd : pixels_per_degree(ViewingConditions{});
        if (auto ok = check_pixels_per_degree(ppd); !ok) return usage_error("--ppd: " + ok.error().message);
        auto size = size_option("--size", o->size);
        if (!size) return usage_error(size.error().message);
        auto outputs = OutputSet::prepare(o->out);
        if (!outputs) return report_error(outputs.error().message);
        // The paper's rows are 3x3 neighborhoods; n5 on request.
        if (o->selection.manifest.empty() && o->selection.neighborhoods.empty()) o->selection.neighborhoods = {"n9"};
        auto specs = o->selection.select();
        if (!specs) return report_error(specs.error().message);
        warn_fitted_space(*specs, o->resolve.color_map, "this run (--color-map)");
        // A scene given twice would only give the same rows twice.
        if (auto misuse = o->choice.misuse()) return usage_error(*misuse);
        const bool builtin = o->sequences.empty() || !o->choice.scenes.empty() || !o->choice.backgrounds.empty();
        auto context = Context::create({o->device, o->validation});
        if (!context) return report_error(context.error().message);
        // Every size is checked against the device and memory before any frame is made or read.
        if (builtin)
            if (auto ok = check_measurable(**context, size->first, size->second, !o->cpu_flip); !ok)
                return usage_error(fmt::format("--size {}: {}", o->size, ok.error().message));
        if (auto ok = check_distinct_files(o->sequences, "--sequence"); !ok) return usage_error(ok.error().message);
        std::vector<SequenceFrames> sequences;
        for (const std::string& dir : o->sequences) {
            auto sequence = read_resolvable_sequence(dir, o->warmup, o->resolve);
            if (!sequence) return report_error(sequence.error().message);
            if (auto ok = check_measurable(**context, sequence->width, sequence->height, !o->cpu_flip); !ok)
                return report_error(fmt::format("--sequence {}: {}", dir, ok.error().message));
            sequences.emplace_back(std::move(*sequence), o->input_space);
        }
        std::vector<std::shared_ptr<const TaaScene>> scenes;
        if (builtin) {
            auto selected = o->choice.select(size->first, size->second, o->seed, o->input_space, context->get());
            if (!selected) return report_error(selected.error().message);
            scenes = std::move(*selected);
        }
        std::set<std::string> names;
        for (const auto& scene : scenes) names.insert(scene->name());
        for (const SequenceFrames& sequence : sequences)
            if (!names.insert(sequence.name()).second)
                return report_error(fmt::format("--sequence: {}: a scene or sequence is already called '{}'",
                                                sequence.sequence().dir.string(), sequence.name()));
        const bool any_hdr = std::any_of(sequences.begin(), sequences.end(),
                                         [](const SequenceFrames& s) { return s.color_range() == ColorRange::hdr; });
        for (const CLI::Option* option : hdr_options)
            if (option->count() && !any_hdr)
                return usage_error(
                    fmt::format("{}: only HDR sequences (\"color\": {{\"range\": \"hdr\"}} in "
                                "sequence.json) are measured in HDR-FLIP, and no --sequence given is one",
                                option->get_name()));
        auto sources = o->selection.set_sources();
        if (!sources) return report_error(sources.error().message);
        auto catalog = VariantCatalog::create(*sources, o->selection.style());
        if (!catalog) return report_error(catalog.error().message);

        // One resolve per variant and depth convention (only --dilate-motion reads depth).
        std::vector<std::unique_ptr<RunnableVariant>> shaders[2];
        auto shader_for = [&](std::size_t v, bool nearer_larger) -> Result<const Variant*> {
            auto& built = shaders[o->resolve.dilate_motion && nearer_larger ? 1 : 0];
            if (built.empty()) {
                ResolveOptions options = o->resolve;
                options.depth_nearer_larger = o->resolve.dilate_motion && nearer_larger;
                for (const VariantSpec& spec : *specs) {
                    auto shader = build_taa_shader(spec, options);
                    if (!shader) return std::unexpected(shader.error());
                    built.push_back(std::move(*shader));
                }
            }
            return &built[v]->variant();
        };
        if (auto first = shader_for(0, false); !first) return report_error(first.error().message);
        std::vector<VariantKey> keys;
        for (const VariantSpec& spec : *specs) keys.push_back(spec.key());
        auto rectifiers = catalog->find_all(keys, o->selection.manifest.empty() ? "--sets" : "--manifest");
        if (!rectifiers) return report_error(rectifiers.error().message);

        // The rectification is timed at the frame size of what is measured: --size, or, with
        // sequences only, the first sequence's.
        const std::uint32_t width = builtin ? size->first : sequences.front().width();
        const std::uint32_t height = builtin ? size->second : sequences.front().height();
        const TaaSchedule schedule{o->warmup, o->frames};
        const HdrFlip cpu_flip(ppd);
        const LdrFlip& flip = cpu_flip.ldr();
        // Ghosting and shimmer on the device by default: one evaluator per frame size, made when a
        // scene or sequence of that size first needs it.
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::unique_ptr<DeviceFlip>> device_flips;
        auto flip_mean = [&](std::uint32_t w, std::uint32_t h) -> Result<FlipMean> {
            if (o->cpu_flip) return cpu_flip_mean(cpu_flip, o->exposure);
            std::unique_ptr<DeviceFlip>& device = device_flips[{w, h}];
            if (!device) {
                auto created = DeviceFlip::create(**context, ppd, w, h);
                if (!created) return std::unexpected(created.error());
                device = std::move(*created);
            }
            return device_flip_mean(*device, o->exposure);
        };
        StagedImages written_frames;
        auto write_frame = [&](const std::string& sequence, std::size_t v) {
            return [&, sequence, v](std::size_t index, const Image& output) -> Result<void> {
                if (!o->write_frames) return {};
                return written_frames.add(fmt::format("frames/{}/{}/{:04}.exr", sequence, keys[v].name(), index),
                                          output);
            };
        };

        std::vector<TaaRow> rows;
        std::vector<std::string> pictures;
        std::vector<std::pair<std::string, std::string>> scene_contents;
        for (const auto& scene : scenes) scene_contents.emplace_back(scene->name(), scene->content());
        {
            // Two lines, each with its own estimate: a timing round takes a fraction of a variant's TAA.
            Result<bench::TimingRun> timing;
            {
                Progress timing_progress(
                    fmt::format("timing {} variants on {},", specs->size(), (*context)->device_name()),
                    o->timing_rounds);
                timing =
                    bench::time_interleaved(**context, *rectifiers, width, height, o->timing_rounds, timing_progress);
                if (!timing) return report_error(timing.error().message);
            }
            Progress progress(fmt::format("TAA of {} variants x {} scenes and sequences on {},", specs->size(),
                                          scenes.size() + sequences.size(), (*context)->device_name()),
                              specs->size() * (scenes.size() + sequences.size()));
            auto row = [&](std::size_t v, const std::string& scene, double shimmer, double ghosting,
                           const char* against, ColorRange range) {
                rows.push_back({keys[v], scene, median(timing->ms[v]), quantile(timing->ms[v], 0.25),
                                quantile(timing->ms[v], 0.75), shimmer, ghosting, against, range});
            };
            for (const auto& scene_pointer : scenes) {
                const TaaScene& scene = *scene_pointer;
                std::vector<std::shared_ptr<const Image>> trails;
                const std::uint32_t w = scene.width(), h = scene.height();
                auto mean = flip_mean(w, h);
                if (!mean) return report_error(fmt::format("{}: {}", scene.name(), mean.error().message));
                for (std::size_t v = 0; v < specs->size(); ++v) {
                    auto resolve = TaaResolve::create(**context, **shader_for(v, false), w, h, o->resolve);
                    if (!resolve) return report_error(resolve.error().message);
                    SceneOutputObserver written = [&](const std::string& sequence, std::size_t index,
                                                      const Image& output) {
                        return write_frame(sequence, v)(index, output);
                    };
                    auto m = measure_scene(**resolve, scene, schedule, *mean, written);
                    if (!m)
                        return report_error(
                            fmt::format("{} on {}: {}", keys[v].name(), scene.name(), m.error().message));
                    row(v, scene.name(), m->shimmer, m->ghosting, m->against_reference ? "reference" : "aliased",
                        ColorRange::ldr);
                    trails.push_back(std::make_shared<const Image>(std::move(m->trail)));
                    progress.advance(fmt::format("{} on {}", keys[v].name(), scene.name()));
                }
                auto shown = ghosting_frames(scene, schedule)->frame(scene.trail_frame(schedule));
                if (!shown) return report_error(shown.error().message);
                const bool has_reference = shown->reference.has_value();
                auto truth = std::make_shared<const Image>(std::move(has_reference ? *shown->reference : shown->color));
                std::vector<double> ghosting;
                for (std::size_t v = rows.size() - keys.size(); v < rows.size(); ++v)
                    ghosting.push_back(rows[v].ghosting);
                if (auto ok = add_trail_outputs(*outputs, scene, has_reference ? "reference" : "aliased", truth, keys,
                                                trails, ghosting, flip, schedule);
                    !ok)
                    return report_error(ok.error().message);
                pictures.push_back(trail_picture_name(scene.name()));
            }
            std::set<std::string> warned; // HDR-FLIP's notes, once however many variants meet them
            for (const SequenceFrames& sequence : sequences) {
                auto mean = flip_mean(sequence.width(), sequence.height());
                if (!mean) return report_error(fmt::format("{}: {}", sequence.name(), mean.error().message));
                for (std::size_t v = 0; v < specs->size(); ++v) {
                    auto shader = shader_for(v, sequence.sequence().depth_nearer_larger);
                    if (!shader) return report_error(shader.error().message);
                    auto resolve =
                        TaaResolve::create(**context, **shader, sequence.width(), sequence.height(), o->resolve);
                    if (!resolve) return report_error(resolve.error().message);
                    auto m =
                        measure_sequence(**resolve, sequence, o->warmup, *mean, {}, write_frame(sequence.name(), v));
                    if (!m)
                        return report_error(
                            fmt::format("{} on {}: {}", keys[v].name(), sequence.name(), m.error().message));
                    row(v, sequence.name(), m->shimmer, m->ghosting, m->against_reference ? "reference" : "aliased",
                        m->range);
                    for (const std::string& note : m->notes)
                        if (warned.insert(note).second) std::cerr << "warning: " << terminal_text(note) << "\n";
                    progress.advance(fmt::format("{} on {}", keys[v].name(), sequence.name()));
                }
            }
        }
        outputs->add(written_frames.writers(outputs->dir()));
        report_validation_messages(**context);

        RunMetadata run_info = describe_run(**context);
        run_info.seed = o->seed;
        // A chart that fails costs the charts, not the run: the data, report and pictures are still written.
        std::vector<std::string> charts;
        if (charts_available(!o->no_charts)) {
            ScratchDirectory scratch("kdop-taa");
            auto drawn = scratch.path.empty() ? Result<std::vector<OutputFile>>(fail("no scratch directory"))
                                              : taa_charts(rows, scratch.path, outputs->dir());
            if (drawn) {
                outputs->add(std::move(*drawn));
                charts = taa_chart_names(rows);
            } else {
                warn_no_charts(drawn.error().message);
            }
        }
        outputs->add_table("taa", taa_table(rows), run_info);
        outputs->add("report.md",
                     taa_report_markdown(rows, run_info,
                                         {width, height, o->warmup, o->frames, ppd, pictures, charts, o->resolve,
                                          scene_contents, sequence_names(sequences), !o->cpu_flip, o->exposure}));
        if (auto ok = outputs->write(); !ok) return report_error(ok.error().message);
        std::cout << fmt::format("kdop taa: {} variants x {} scenes and sequences on {} ({}): {}\n", specs->size(),
                                 scenes.size() + sequences.size(), run_info.device, run_info.driver,
                                 terminal_text((outputs->dir() / "report.md").string()));
        return 0;
    };
}

} // namespace kdop::cli
