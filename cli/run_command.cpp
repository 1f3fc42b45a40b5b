#include "cli/commands.h"

#include "cli/input_space_option.h"
#include "cli/number_option.h"
#include "cli/variant_option.h"
#include "core/shown_text.h"
#include "harness/rectify_run.h"
#include "harness/statistics.h"
#include "harness/variant_catalog.h"

#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <optional>

namespace kdop::cli {

Action add_run_command(CLI::App& app) {
    struct Options {
        std::string variant, current, history, out, format = "rgba32f", device, numerics;
        std::vector<std::string> sets;
        std::optional<double> gamma;
        unsigned repeat = 1;
        InputSpace input_space = InputSpace::from_file;
    };
    auto o = std::make_shared<Options>();
    CLI::App* run = app.add_subcommand(
        "run", "Run one variant on a current frame and a history on the GPU, write the rectified history");
    run->add_option("--variant", o->variant,
                    "Variant name (see `kdop list --all`), of a built-in set or of one given with --sets")
        ->required();
    run->add_option("--sets", o->sets, "Axis-set files whose variants --variant may name");
    run->add_option(
           "--numerics", o->numerics,
           "hardened, or paper: the variant with the supplement's numerics (the same as naming <variant>-paper)")
        ->check(CLI::IsMember({"hardened", "paper"}));
    run->add_option("--current", o->current,
                    "Current frame (any OpenImageIO format; RGB from the first three channels)")
        ->required();
    run->add_option("--history", o->history, "History, the same size as the current frame")->required();
    add_input_space_option(*run, o->input_space);
    run->add_option(
           "--out", o->out,
           "Rectified history to write (EXR keeps floats; PNG keeps 0..1 in 8 bits, sRGB-encoded, and refuses other "
           "values; lossy formats are refused)")
        ->required();
    run->add_option("--gamma", o->gamma,
                    "Variance-clip slab half-width in standard deviations (varclip only) [default: 1]")
        ->check(gamma_number());
    run->add_option("--format", o->format, "Texture format the inputs are uploaded in: rgba32f or rgba16f");
    run->add_option(
        "--device", o->device,
        "Vulkan device: a substring of its name, or gpu for the first GPU [default: $KDOP_DEVICE, else lavapipe]");
    run->add_option("--repeat", o->repeat,
                    "Dispatch this many times and report pipeline creation and median dispatch time")
        ->check(whole_number(1, 100000));

    return [o] {
        auto key = variant_option(o->variant, o->numerics, "--variant");
        if (!key) return usage_error(key.error().message);
        auto catalog = VariantCatalog::create(o->sets);
        if (!catalog) return report_error(catalog.error().message);
        auto variant = catalog->find(*key);
        if (!variant) return report_error(variant.error().message);
        auto format = parse_texture_format(o->format);
        if (!format) return usage_error(fmt::format("--format: '{}' is not rgba32f or rgba16f", o->format));

        auto run = run_rectify(
            **variant,
            {o->current, o->history, o->out, o->input_space, *format, o->gamma, o->repeat, {o->device, false}});
        if (!run) return report(run.error());
        std::cout << fmt::format("{} on {}: {}x{} {} -> {}\n", (*variant)->name, run->device, run->width, run->height,
                                 to_string(*format), terminal_text(o->out));
        if (o->repeat > 1) {
            const double pixels = double(run->width) * run->height;
            const double wall = median(run->wall_ms), device = median(run->device_ms);
            // The first dispatch is reported apart: drivers may finish compiling the pipeline there.
            std::cout << fmt::format("pipeline creation {:.1f} ms, first dispatch {:.2f} ms; {} dispatches: median "
                                     "{:.2f} ms wall ({:.1f} Mpixel/s), {:.2f} ms device\n",
                                     run->creation_ms, run->wall_ms.front(), o->repeat, wall, pixels / wall * 1e-3,
                                     device);
        }
        return 0;
    };
}

} // namespace kdop::cli
