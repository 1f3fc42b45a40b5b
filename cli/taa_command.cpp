#include "cli/commands.h"

#include "cli/hdr_flip_option.h"
#include "cli/input_space_option.h"
#include "cli/number_option.h"
#include "cli/own_resolve_option.h"
#include "cli/resolve_option.h"
#include "cli/scene_options.h"
#include "cli/size_option.h"
#include "core/shown_text.h"
#include "generator/command_line.h"
#include "generator/selection_options.h"
#include "harness/output_set.h"
#include "harness/ranks.h"
#include "harness/variant_catalog.h"
#include "sequence/sequence.h"
#include "sequence/sequence_corpus.h"
#include "temporal/metrics.h"
#include "temporal/taa_run.h"

#include <fmt/format.h>

#include <iostream>
#include <memory>

namespace kdop::cli {

namespace {

struct TaaOptions {
    std::string out, size = "320x180", device, nss_sequence, nss_range = "hdr";
    double ratio = 2.0;
    std::vector<std::string> sequences, metrics{"shimmer", "ghosting"};
    SceneChoice choice;
    SelectionOptions selection;
    std::uint32_t warmup = 100, frames = 100;
    unsigned timing_rounds = 15;
    std::size_t viewer_frames = 8, picture_frame = 0;
    std::uint64_t seed = 1;
    double ppd = 0;
    bool validation = false, no_charts = false, write_frames = false, cpu_flip = false;
    InputSpace input_space = InputSpace::from_file;
    ResolveOptions resolve;
    OwnResolveOptions own_resolve;
    ExposureOptions exposure; // HDR-FLIP's, for HDR sequences
};

// taa's subcommand and its options, read into `o`; the options a later check needs by name.
struct TaaDeclared {
    CLI::App* taa;
    std::vector<CLI::Option*> hdr_options;
    CLI::Option* picture_frame;
    CLI::Option* ratio;
    CLI::Option* nss_range;
};
TaaDeclared declare_taa(CLI::App& app, TaaOptions* o) {
    CLI::App* taa = app.add_subcommand(
        "taa", "Run every variant in one TAA resolve on the device over kdop's scenes or your own frame sequences "
               "and measure the ghosting and shimmer a viewer sees, in LDR-FLIP (HDR sequences in HDR-FLIP), as Ikkala "
               "et al. 2024 do (Tables 1 and 2); writes taa.csv (and JSON), report.md, report.html (the table, "
               "charts and a frame viewer), selected frames as EXR and PNG and a labeled ghosting picture per scene "
               "and sequence; under mpirun, the scenes and sequences over ranks");
    taa->add_option("--out", o->out, "Output directory (created if missing)")->required();
    o->selection.add_to(*taa, true, kCommandDefaults);
    o->choice.add_to(*taa, true);
    taa->add_option("--sequence", o->sequences,
                    "Frame sequences to measure: each a folder with sequence.json (docs/taa.md, \"Frame "
                    "sequences\"), a folder of such folders, or a list file of them, one folder a line (\"Many "
                    "sequences\"); with --sequence, kdop's own scenes run only if --scenes or --background is given "
                    "too");
    taa->add_option("--nss-sequence", o->nss_sequence,
                    "Read the one --sequence folder as the root of an Arm NSS dataset capture and measure its "
                    "sequence NNNN (NNNN.json, ground_truth/NNNN, x<ratio>/{color,depth,motion}/NNNN; docs/taa.md, "
                    "\"NSS captures\"), or with all every sequence there");
    CLI::Option* ratio = taa->add_option("--ratio", o->ratio,
                                         "With --nss-sequence: the capture's upscaling ratio, whose x<ratio> folder "
                                         "holds the frames (2, 1.7, 1.5, 1.3) [default: 2]")
                             ->check(finite_number(1, 8));
    CLI::Option* nss_range =
        taa->add_option("--nss-range", o->nss_range,
                        "With --nss-sequence: the range of the capture's colors: hdr (linear values from 0 up, as "
                        "NSS captures are), measured in HDR-FLIP; or ldr (values from 0 to 1, such as kdop scene "
                        "--layout nss writes of kdop's scenes), measured in LDR-FLIP as the scenes are in memory, a "
                        "value outside [0, 1] refused, naming its file and pixel, never clamped [default: hdr]")
            ->check(CLI::IsMember({"hdr", "ldr"}));
    add_input_space_option(*taa, o->input_space);
    add_resolve_options(*taa, o->resolve);
    add_own_resolve_options(*taa, o->own_resolve);
    taa->add_flag("--write-frames", o->write_frames,
                  "Also write every measured output as EXR, frames/<sequence>/<variant>/NNNN.exr (kdop's scenes: "
                  "<scene>-shimmer and <scene>-ghosting)");
    taa->add_option("--viewer-frames", o->viewer_frames,
                    "Frames of each sequence report.html's viewer shows, spread evenly, besides each variant's "
                    "worst; 0: no viewer [default: 8]")
        ->check(whole_number(0, 1000));
    CLI::Option* picture_frame =
        taa->add_option("--picture-frame", o->picture_frame,
                        "The frame each sequence's ghosting picture shows [default: where the variants differ most]")
            ->check(whole_number(0, 1000000));
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
    taa->add_option("--seed", o->seed,
                    "Seed of the synthetic textures, the 3-D scenes and the bootstrap intervals [default: 1]")
        ->check(seed_number());
    taa->add_option(
        "--device", o->device,
        "Vulkan device: a substring of its name, or gpu for the first GPU [default: $KDOP_DEVICE, else lavapipe]");
    taa->add_flag("--validation", o->validation, "Enable the Khronos validation layer (slower)");
    taa->add_flag("--cpu-flip", o->cpu_flip,
                  "Measure ghosting and shimmer with the CPU's FLIP, the reference code the device's is tested "
                  "against, instead of on the device");
    // HDR sequences ("color": {"range": "hdr"}) are measured in HDR-FLIP at these.
    const std::vector<CLI::Option*> hdr_options = add_hdr_flip_options(*taa, o->exposure);
    taa->add_flag("--no-charts", o->no_charts, "Write the tables, report and pictures without the trade charts");
    taa->add_option("--metrics", o->metrics,
                    fmt::format("What each output is measured with: {} (docs/taa.md, \"Metrics\"); psnr and tpsnr "
                                "only where a sequence has reference frames [default: shimmer ghosting, the paper's]",
                                metric_names(default_metrics())));

    return {taa, hdr_options, picture_frame, ratio, nss_range};
}

} // namespace

Action add_taa_command(CLI::App& app) {
    auto o = std::make_shared<TaaOptions>();
    const TaaDeclared declared = declare_taa(app, o.get());
    CLI::App* taa = declared.taa;
    CLI::Option* picture_frame = declared.picture_frame;
    const std::vector<CLI::Option*> hdr_options = declared.hdr_options;
    CLI::Option* ratio = declared.ratio;
    CLI::Option* nss_range = declared.nss_range;
    return [o, taa, hdr_options, picture_frame, ratio, nss_range] {
        if (o->selection.baselines)
            return report_error("--baselines: the gather and copy baselines are not clips; they have no place in TAA");
        const double ppd = taa->count("--ppd") ? o->ppd : pixels_per_degree(ViewingConditions{});
        if (auto ok = check_pixels_per_degree(ppd); !ok) return usage_error("--ppd: " + ok.error().message);
        auto metrics = metrics_named(o->metrics);
        if (!metrics) return usage_error("--metrics: " + metrics.error().message);
        if (ratio->count() && o->nss_sequence.empty())
            return usage_error("--ratio: picks the folder of an NSS capture's frames, and needs --nss-sequence");
        if (nss_range->count() && o->nss_sequence.empty())
            return usage_error("--nss-range: says the range of an NSS capture's colors, and needs --nss-sequence");
        if (!o->nss_sequence.empty() && o->sequences.size() != 1)
            return usage_error(fmt::format("--nss-sequence {}: needs the capture's root folder as one --sequence ({} "
                                           "given)",
                                           o->nss_sequence, o->sequences.size()));
        auto size = size_option("--size", o->size);
        if (!size) return usage_error(size.error().message);
        // A folder of sequences or a list file stands for the sequences it names (an NSS root is one).
        std::vector<std::string> sequences = o->sequences;
        if (o->nss_sequence.empty()) {
            auto expanded = expand_sequence_arguments(o->sequences, "--sequence");
            if (!expanded) return report_error(expanded.error().message);
            sequences = std::move(*expanded);
        }
        OwnResolveChoice own = own_resolve_choice(*taa, o->own_resolve);
        if (!own.usage.empty()) return usage_error(own.usage);
        if (!own.input.empty()) return report_error(own.input);
        // Under mpirun every rank runs this; only rank 0 speaks and writes (taa_ranks.h). What a rank
        // alone may fail at (its folder, device, files) is agreed on, so none waits for one that left.
        auto ranks = Ranks::world();
        if (!ranks) return report_error(ranks.error().message);
        (*ranks)->quiet_unless_root();
        auto agreed = [&](auto&& result) {
            return (*ranks)->agree(result ? Result<void>{} : std::unexpected(result.error()));
        };
        auto outputs = OutputSet::prepare(o->out);
        if (auto ok = agreed(outputs); !ok) return report_error(ok.error().message);
        auto specs = o->selection.select();
        if (!specs) return report_error(specs.error().message);
        warn_fitted_space(*specs, o->resolve.color_map, "this run (--color-map)");
        // A scene given twice would only give the same rows twice.
        if (auto misuse = o->choice.misuse()) return usage_error(*misuse);
        auto context = Context::create({o->device, o->validation});
        if (auto ok = agreed(context); !ok) return report_error(ok.error().message);
        auto sources = taa_sources(
            **context, {.sequences = sequences,
                        .warmup = o->warmup,
                        .resolve = o->resolve,
                        .own_reads_depth = own.resolve && own.resolve->reads_depth(),
                        .input_space = o->input_space,
                        .device_flip = !o->cpu_flip,
                        .variants = specs->size(),
                        .builtin = o->sequences.empty() || !o->choice.scenes.empty() || !o->choice.backgrounds.empty(),
                        .scene_names = o->choice.scenes,
                        .backgrounds = o->choice.backgrounds,
                        .scene_options = o->choice.options(size->first, size->second, o->seed, o->input_space),
                        .picture_frame = picture_frame->count() ? std::optional(o->picture_frame) : std::nullopt,
                        .nss_sequence = o->nss_sequence,
                        .nss_ratio = o->ratio,
                        .nss_range = o->nss_range == "ldr" ? ColorRange::ldr : ColorRange::hdr});
        if (auto ok = agreed(sources); !ok) return report(ok.error());
        for (const SequenceFrames& sequence : sources->sequences)
            if (auto ok = check_outside(sequence.sequence(), outputs->dir(), "--out"); !ok) return report(ok.error());
        for (const NssFrames& capture : sources->captures)
            if (auto ok = check_outside(capture.capture(), outputs->dir(), "--out"); !ok) return report(ok.error());
        for (const CLI::Option* option : hdr_options)
            if (option->count() && !sources->any_hdr())
                return usage_error(
                    fmt::format("{}: only HDR sequences (\"color\": {{\"range\": \"hdr\"}} in "
                                "sequence.json) are measured in HDR-FLIP, and no --sequence given is one",
                                option->get_name()));
        auto set_sources = o->selection.set_sources();
        if (!set_sources) return report_error(set_sources.error().message);
        auto catalog = VariantCatalog::create(*set_sources, o->selection.style());
        if (!catalog) return report_error(catalog.error().message);

        auto rectifiers = catalog->find_all(keys_of(*specs), o->selection.manifest.empty() ? "--sets" : "--manifest");
        if (auto ok = agreed(rectifiers); !ok) return report_error(ok.error().message);
        const TaaRunSettings settings{.evaluation = {.resolve = o->resolve,
                                                     .schedule = {o->warmup, o->frames},
                                                     .ppd = ppd,
                                                     .cpu_flip = o->cpu_flip,
                                                     .exposure = o->exposure,
                                                     .metrics = *metrics,
                                                     .spatial_upscale = true,
                                                     .own_resolve = std::move(own.resolve)},
                                      .width = size->first,
                                      .height = size->second,
                                      .timing_rounds = o->timing_rounds,
                                      .seed = o->seed,
                                      .write_frames = o->write_frames,
                                      .charts = !o->no_charts,
                                      .viewer_frames = o->viewer_frames,
                                      .picture_frame =
                                          picture_frame->count() ? std::optional(o->picture_frame) : std::nullopt};
        auto run_info = run_taa(**context, *specs, *rectifiers, *sources, settings, *outputs, **ranks);
        report_validation_messages((*context)->validation_messages());
        if (!run_info) return report_error(run_info.error().message);
        if (!(*ranks)->is_root()) return 0;
        std::cout << fmt::format("kdop taa: {} variants x {} scenes and sequences on {} ({}): {}\n", specs->size(),
                                 sources->size(), run_info->device, run_info->driver,
                                 terminal_text((outputs->dir() / "report.md").string()));
        return 0;
    };
}

} // namespace kdop::cli
