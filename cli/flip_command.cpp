#include "commands.h"

#include "color_spaces.h"
#include "command_line.h"
#include "flip.h"
#include "image_io.h"
#include "input_files.h"
#include "input_space_option.h"
#include "magma.h"
#include "memory_budget.h"
#include "number_option.h"
#include "write_files.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>

namespace kdop::cli {

Action add_flip_command(CLI::App& app) {
    struct Options {
        std::string reference, test, out;
        double ppd = 0;
        ViewingConditions viewing;
        bool srgb = false;
        InputSpace input_space = InputSpace::from_file;
    };
    auto o = std::make_shared<Options>();
    CLI::App* flip = app.add_subcommand(
        "flip", "LDR-FLIP (Andersson et al. 2020): the difference a viewer sees flipping between a reference and a "
                "test image; prints the mean, writes the per-pixel map with --out");
    flip->add_option("--reference", o->reference,
                     "Reference image (any OpenImageIO format; RGB from 0 to 1 once decoded, see --input-space)")
        ->required();
    flip->add_option("--test", o->test, "Test image, the same size as the reference")->required();
    auto* ppd = flip->add_option("--ppd", o->ppd,
                                 fmt::format("Pixels per degree of visual angle, from {} to {} [default: from the "
                                             "viewing conditions, about 67]",
                                             kMinPixelsPerDegree, kMaxPixelsPerDegree))
                    ->check(finite_number(kMinPixelsPerDegree, kMaxPixelsPerDegree));
    flip->add_option("--distance", o->viewing.distance_m, "Viewing distance in meters [default: 0.7]")
        ->check(positive_number(1e6))
        ->excludes(ppd);
    flip->add_option("--display-width", o->viewing.display_width_m, "Display width in meters [default: 0.7]")
        ->check(positive_number(1e6))
        ->excludes(ppd);
    flip->add_option("--display-pixels", o->viewing.display_width_px, "Display width in pixels [default: 3840]")
        ->check(positive_number(1e6))
        ->excludes(ppd);
    auto* space = add_input_space_option(*flip, o->input_space);
    flip->add_flag("--srgb", o->srgb, "The same as --input-space srgb: decode every input from sRGB")->excludes(space);
    flip->add_option("--out", o->out,
                     "Error map to write: .exr holds the values (gray), .png shows them in the magma color map");

    return [o, ppd] {
        const bool viewing = !*ppd;
        const double pixels_per_degree = viewing ? kdop::pixels_per_degree(o->viewing) : o->ppd;
        if (auto ok = check_pixels_per_degree(pixels_per_degree); !ok)
            return usage_error(viewing ? fmt::format("--distance {} --display-width {} --display-pixels {}: {}",
                                                     o->viewing.distance_m, o->viewing.display_width_m,
                                                     o->viewing.display_width_px, ok.error().message)
                                       : fmt::format("--ppd: {}", ok.error().message));
        bool magma = false;
        if (!o->out.empty()) {
            std::string extension = std::filesystem::path(o->out).extension().string();
            std::ranges::transform(extension, extension.begin(), [](unsigned char c) { return std::tolower(c); });
            if (extension != ".exr" && extension != ".png")
                return usage_error(fmt::format(
                    "--out: {}: the map is written as .exr (its values) or .png (in magma colors)", o->out));
            magma = extension == ".png";
            if (std::error_code ec; std::filesystem::is_directory(o->out, ec))
                return usage_error(fmt::format("--out {}: is a directory; name the map's file", o->out));
            const std::filesystem::path inputs[] = {o->reference, o->test};
            if (auto ok = check_not_an_input(o->out, "--out", inputs); !ok) return report_error(ok.error().message);
            if (auto ok = check_output_directory(std::filesystem::path(o->out).parent_path(), "--out"); !ok)
                return report_error(ok.error().message);
        }

        const InputSpace input_space = o->srgb ? InputSpace::srgb : o->input_space;
        auto reference = read_image(o->reference, 0, input_space);
        if (!reference) return report_error(reference.error().message);
        auto test = read_image(o->test, 0, input_space);
        if (!test) return report_error(test.error().message);
        if (test->width != reference->width || test->height != reference->height)
            return report_error(fmt::format("--test {}: {}x{}, but --reference {} is {}x{}", o->test, test->width,
                                            test->height, o->reference, reference->width, reference->height));
        if (auto ok = check_ldr_image(*reference, "--reference " + o->reference); !ok)
            return report_error(ok.error().message);
        if (auto ok = check_ldr_image(*test, "--test " + o->test); !ok) return report_error(ok.error().message);
        if (auto ok = check_memory(
                fmt::format("--reference {}: LDR-FLIP of {}x{}", o->reference, reference->width, reference->height),
                ldr_flip_bytes(reference->width, reference->height) + image_bytes(reference->width, reference->height));
            !ok)
            return report_error(ok.error().message);

        const LdrFlip evaluator(pixels_per_degree);
        auto map = evaluator.error_map(*reference, *test);
        if (!map) return report_error(map.error().message);
        std::cout << fmt::format("LDR-FLIP mean {} at {:.4g} pixels per degree ({}x{}{})\n", mean_error(*map),
                                 pixels_per_degree, reference->width, reference->height,
                                 input_space == InputSpace::srgb     ? ", every input decoded from sRGB"
                                 : input_space == InputSpace::linear ? ", every input taken as linear"
                                                                     : "");
        if (o->out.empty()) return 0;

        const std::uint32_t w = reference->width, h = reference->height;
        Image image(w, h);
        if (magma) {
            image = flip::magma_image(*map, w, h);
        } else {
            for (std::size_t i = 0; i < map->size(); ++i) image.pixels[i] = glm::vec4(glm::vec3((*map)[i]), 1.0f);
        }
        if (auto ok = write_image(o->out, image); !ok) return report_error(ok.error().message);
        std::cout << fmt::format("wrote {}\n", o->out);
        return 0;
    };
}

} // namespace kdop::cli
