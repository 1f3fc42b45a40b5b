#include "cli/commands.h"

#include "cli/input_space_option.h"
#include "cli/number_option.h"
#include "cli/scene_options.h"
#include "cli/size_option.h"
#include "core/shown_text.h"
#include "harness/output_set.h"
#include "scenes/scene_export.h"
#include "sequence/nss_writer.h"

#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <optional>
#include <string>

namespace kdop::cli {
namespace {

// "on" or "off", for --jitter and --animate.
CLI::Validator on_or_off() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            return text == "on" || text == "off" ? "" : "'" + text + "' is not on or off";
        },
        "on|off");
}

} // namespace

Action add_scene_command(CLI::App& app) {
    struct Options {
        std::string out, size = "320x180", jitter, animate, layout = "kdop", nss_precision = "half";
        SceneChoice choice;
        std::uint32_t frames = 200;
        std::uint64_t seed = 1;
        InputSpace input_space = InputSpace::from_file;
    };
    auto o = std::make_shared<Options>();
    CLI::App* scene = app.add_subcommand(
        "scene", "Write kdop's own TAA scenes as frame sequences (docs/taa.md, \"Frame sequences\"): color, motion and "
                 "depth per frame (and a supersampled reference with --reference-samples), exactly the frames "
                 "kdop taa measures, to look at, edit or replay with kdop taa --sequence");
    scene
        ->add_option("--out", o->out,
                     "Output directory (created if missing): one folder per sequence; with --layout nss, the NSS "
                     "dataset's root")
        ->required();
    o->choice.add_to(*scene, true);
    add_input_space_option(*scene, o->input_space);
    scene->add_option("--size", o->size, "Frame size WIDTHxHEIGHT [default: 320x180]");
    scene->add_option("--frames", o->frames, "Frames per sequence [default: 200, kdop taa's warmup and frames]")
        ->check(whole_number(1, 100000));
    scene->add_option("--seed", o->seed, "Seed of the synthetic textures and the 3-D scenes [default: 1]")
        ->check(seed_number());
    scene
        ->add_option("--jitter", o->jitter,
                     "Jitter the samples (R2) [with neither --jitter nor --animate: two sequences per scene, "
                     "<scene>-shimmer (jitter on, still) and <scene>-ghosting (moving, jitter off), as kdop taa "
                     "measures them; with either, one sequence <scene>, the other on]")
        ->check(on_or_off());
    scene->add_option("--animate", o->animate, "Move the objects (see --jitter)")->check(on_or_off());
    scene
        ->add_option("--layout", o->layout,
                     "kdop: kdop's sequence format, a folder per sequence with sequence.json; nss: Arm's NSS dataset "
                     "capture layout (docs/taa.md, \"NSS captures\"), the sequences numbered 0000, 0001, ... in the "
                     "order printed (and named in kdop_sequences.json): NNNN.json, ground_truth/NNNN, motion_gt/NNNN, "
                     "x<ratio>/{color,depth,motion}/NNNN, the ratio --upscale's; every frame needs a reference, so "
                     "only 3-D scenes with --reference-samples or --upscale [default: kdop]")
        ->check(CLI::IsMember({"kdop", "nss"}));
    CLI::Option* precision =
        scene
            ->add_option("--nss-precision", o->nss_precision,
                         "With --layout nss: half (16-bit floats, the spec's R16G16B16A16_SFLOAT) or float (32-bit, "
                         "which a reading gives back exactly) for color, ground truth, motion and motion_gt; depth "
                         "is 32-bit either way [default: half]")
            ->check(CLI::IsMember({"half", "float"}));

    return [o, precision] {
        auto size = size_option("--size", o->size);
        if (!size) return usage_error(size.error().message);
        if (auto misuse = o->choice.misuse()) return usage_error(*misuse);
        const bool nss = o->layout == "nss";
        if (precision->count() && !nss)
            return usage_error("--nss-precision: the precision of an NSS capture's images, and needs --layout nss");
        // Declared first, so it outlives the outputs' writers, which draw 3-D frames on it.
        std::unique_ptr<Context> context;
        auto outputs = OutputSet::prepare(o->out);
        if (!outputs) return report_error(outputs.error().message);
        if (o->choice.needs_device()) {
            auto created = Context::create({});
            if (!created) return report_error(created.error().message);
            context = std::move(*created);
        }
        auto scenes = o->choice.select(size->first, size->second, o->seed, o->input_space, context.get());
        if (!scenes) return report(scenes.error());

        const auto on = [](const std::string& text) {
            return text.empty() ? std::nullopt : std::optional(text == "on");
        };
        const SceneExportOptions options{.frames = o->frames,
                                         .animate = on(o->animate),
                                         .jitter = on(o->jitter),
                                         .layout = nss ? SceneLayout::nss : SceneLayout::kdop,
                                         .ratio = o->choice.upscale,
                                         .precision =
                                             o->nss_precision == "float" ? FloatPrecision::full : FloatPrecision::half};
        auto written = export_scenes(*scenes, options, *outputs);
        if (!written) return report(written.error());
        std::cout << fmt::format("kdop scene: {} {}sequences of {} frames at {}x{}: {}\n", written->size(),
                                 nss ? "NSS " : "", o->frames, size->first, size->second,
                                 terminal_text(outputs->dir().string()));
        // Which scene became which NSS sequence (also in kdop_sequences.json).
        if (nss)
            for (std::size_t i = 0; i < written->size(); ++i)
                std::cout << fmt::format("  {}: {}\n", nss_sequence_number(i), terminal_text((*written)[i]));
        return 0;
    };
}

} // namespace kdop::cli
