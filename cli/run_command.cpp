#include "cli/commands.h"

#include "cli/input_space_option.h"
#include "cli/number_option.h"
#include "cli/variant_option.h"
#include "core/input_files.h"
#include "core/memory_budget.h"
#include "core/shown_text.h"
#include "core/write_files.h"
#include "harness/statistics.h"
#include "harness/variant_catalog.h"
#include "images/image_io.h"
#include "runtime/context.h"
#include "runtime/kernel.h"
#include "runtime/rectify_pass.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
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
    run->add_option("--device", o->device,
                    "Vulkan device: a substring of its name [default: $KDOP_DEVICE, else lavapipe]");
    run->add_option("--repeat", o->repeat,
                    "Dispatch this many times and report pipeline creation and median dispatch time")
        ->check(whole_number(1, 100000));

    return [o] {
        auto key = variant_option(o->variant, o->numerics, "--variant");
        if (!key) return report_error(key.error().message);
        auto catalog = VariantCatalog::create(o->sets);
        if (!catalog) return report_error(catalog.error().message);
        auto found = catalog->find(*key);
        if (!found) return report_error(found.error().message);
        const Variant* variant = *found;
        auto format = parse_texture_format(o->format);
        if (!format) return usage_error(fmt::format("--format: '{}' is not rgba32f or rgba16f", o->format));
        if (o->gamma && variant->mode != Mode::varclip)
            return usage_error(fmt::format("--gamma: {} is not a variance clip and takes no gamma", variant->name));
        const double gamma = o->gamma.value_or(1.0);
        if (!OIIO::ImageOutput::create(o->out))
            return usage_error(fmt::format("--out: {}: no image format for this extension", o->out));
        const std::filesystem::path inputs[] = {o->current, o->history};
        if (auto ok = check_output_file(o->out, "--out"); !ok) return usage_error(ok.error().message);
        if (auto ok = check_not_an_input(o->out, "--out", inputs); !ok) return report_error(ok.error().message);

        // The device first: its size limit is checked on each image's header, before its pixels.
        auto context = Context::create({o->device, false});
        if (!context) return report_error(context.error().message);
        const std::uint32_t max_side = (*context)->properties().limits.maxImageDimension2D;
        auto current = read_image(o->current, max_side, o->input_space);
        if (!current) return report_error(current.error().message);
        auto history = read_image(o->history, max_side, o->input_space);
        if (!history) return report_error(history.error().message);
        if (current->width != history->width || current->height != history->height)
            return report_error(fmt::format("--history: {} is {}x{} but --current {} is {}x{}", o->history,
                                            history->width, history->height, o->current, current->width,
                                            current->height));
        if (auto ok = check_memory(
                fmt::format("--current {}: a {}x{} rectification", o->current, current->width, current->height),
                rectify_pass_bytes(current->width, current->height));
            !ok)
            return report_error(ok.error().message);
        auto kernel = Kernel::create(**context, *variant);
        if (!kernel) return report_error(kernel.error().message);
        auto pass = RectifyPass::create(**context, current->width, current->height, *format);
        if (!pass) return report_error(pass.error().message);
        if (auto ok = (*pass)->upload(*current, *history); !ok) return report_error(ok.error().message);
        std::vector<double> wall_ms, device_ms;
        for (unsigned i = 0; i < o->repeat; ++i) {
            auto timing = (*pass)->dispatch(**kernel, static_cast<float>(gamma));
            if (!timing) return report_error(timing.error().message);
            wall_ms.push_back(timing->wall_ms);
            device_ms.push_back(timing->device_ms);
        }
        auto result = (*pass)->download();
        if (!result) return report_error(result.error().message);
        if (auto ok = write_image(o->out, *result); !ok) return report_error(ok.error().message);
        std::cout << fmt::format("{} on {}: {}x{} {} -> {}\n", variant->name, (*context)->device_name(), current->width,
                                 current->height, to_string(*format), terminal_text(o->out));
        if (o->repeat > 1) {
            const double pixels = double(current->width) * current->height;
            const double wall = median(wall_ms), device = median(device_ms);
            // The first dispatch is reported apart: drivers may finish compiling the pipeline there.
            std::cout << fmt::format("pipeline creation {:.1f} ms, first dispatch {:.2f} ms; {} dispatches: median "
                                     "{:.2f} ms wall ({:.1f} Mpixel/s), {:.2f} ms device\n",
                                     (*kernel)->creation_ms(), wall_ms.front(), o->repeat, wall, pixels / wall * 1e-3,
                                     device);
        }
        return 0;
    };
}

} // namespace kdop::cli
