#include "cli/commands.h"

#include "cli/hdr_flip_option.h"
#include "cli/input_space_option.h"
#include "cli/number_option.h"
#include "core/input_files.h"
#include "core/memory_budget.h"
#include "core/shown_text.h"
#include "core/write_files.h"
#include "flip/color_spaces.h"
#include "flip/device_flip.h"
#include "flip/flip.h"
#include "flip/hdr_flip.h"
#include "flip/magma.h"
#include "generator/command_line.h"
#include "harness/statistics.h"
#include "images/image_io.h"
#include "runtime/context.h"

#include <fmt/format.h>

#include <sys/resource.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

namespace kdop::cli {
namespace {

// What one evaluation gives: the mean, and the maps when a file wants them.
struct FlipResult {
    double mean = 0;
    std::vector<float> map, exposure_map;
    ExposureRange range; // HDR-FLIP's
};

// CPU seconds this process has used, every thread's (lavapipe's included), user and system.
double process_cpu_seconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    auto seconds = [](const timeval& t) { return double(t.tv_sec) + double(t.tv_usec) * 1e-6; };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

} // namespace

Action add_flip_command(CLI::App& app) {
    struct Options {
        std::string reference, test, out;
        double ppd = 0;
        ViewingConditions viewing;
        bool srgb = false;
        InputSpace input_space = InputSpace::from_file;
        bool hdr = false;
        ExposureOptions exposure;
        std::string exposure_map;
        bool cpu = false, validation = false;
        std::string device;
        int timing = 0;
    };
    auto o = std::make_shared<Options>();
    CLI::App* flip = app.add_subcommand(
        "flip", "LDR-FLIP (Andersson et al. 2020), or with --hdr HDR-FLIP (Andersson et al. 2021): the difference a "
                "viewer sees flipping between a reference and a test image; prints the mean, writes the per-pixel map "
                "with --out");
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
    auto* hdr = flip->add_flag("--hdr", o->hdr,
                               "HDR-FLIP: linear RGB from 0 up, compared at a range of exposures after tone mapping");
    for (CLI::Option* option : add_hdr_flip_options(*flip, o->exposure)) option->needs(hdr);
    auto* cpu = flip->add_flag("--cpu", o->cpu,
                               "Compute on the CPU with the reference code the device passes are tested against, not "
                               "on the Vulkan device");
    flip->add_option("--device", o->device,
                     "Vulkan device: a substring of its name [default: $KDOP_DEVICE, else lavapipe]")
        ->excludes(cpu);
    flip->add_flag("--validation", o->validation, "Enable the Khronos validation layer (slower)")->excludes(cpu);
    flip->add_option("--timing", o->timing,
                     "Evaluate N more times after the first and print the median wall and CPU seconds (all threads) "
                     "per evaluation, and the set-up's")
        ->check(whole_number(1, 1000));
    flip->add_option("--exposure-map", o->exposure_map,
                     "HDR-FLIP: write, per pixel, which exposure gave its error (0 the first, 1 the last) to this "
                     ".exr (the values) or .png (in magma colors; the reference tool draws it in viridis)")
        ->needs(hdr);

    return [o, ppd] {
        const bool viewing = !*ppd;
        const double pixels_per_degree = viewing ? kdop::pixels_per_degree(o->viewing) : o->ppd;
        if (auto ok = check_pixels_per_degree(pixels_per_degree); !ok)
            return usage_error(viewing ? fmt::format("--distance {} --display-width {} --display-pixels {}: {}",
                                                     o->viewing.distance_m, o->viewing.display_width_m,
                                                     o->viewing.display_width_px, ok.error().message)
                                       : fmt::format("--ppd: {}", ok.error().message));
        // A map's file: .exr for its values, .png in magma colors; checked before any work.
        const std::filesystem::path inputs[] = {o->reference, o->test};
        auto extension_of = [](const std::string& path) {
            std::string extension = std::filesystem::path(path).extension().string();
            std::ranges::transform(extension, extension.begin(), [](unsigned char c) { return std::tolower(c); });
            return extension;
        };
        auto check_map_file = [&](const std::string& path, const char* option) -> std::optional<int> {
            if (path.empty()) return std::nullopt;
            const std::string extension = extension_of(path);
            if (extension != ".exr" && extension != ".png")
                return usage_error(fmt::format("{}: {}: the map is written as .exr (its values) or .png (in magma "
                                               "colors)",
                                               option, path));
            if (auto ok = check_output_file(path, option); !ok) return usage_error(ok.error().message);
            if (auto ok = check_not_an_input(path, option, inputs); !ok) return report_error(ok.error().message);
            return std::nullopt;
        };
        if (auto failed = check_map_file(o->out, "--out")) return *failed;
        if (auto failed = check_map_file(o->exposure_map, "--exposure-map")) return *failed;
        if (!o->out.empty() && o->out == o->exposure_map)
            return usage_error(fmt::format("--out and --exposure-map both name {}", o->out));

        const InputSpace input_space = o->srgb ? InputSpace::srgb : o->input_space;
        auto reference = read_image(o->reference, 0, input_space);
        if (!reference) return report_error(reference.error().message);
        auto test = read_image(o->test, 0, input_space);
        if (!test) return report_error(test.error().message);
        if (test->width != reference->width || test->height != reference->height)
            return report_error(fmt::format("--test {}: {}x{}, but --reference {} is {}x{}", o->test, test->width,
                                            test->height, o->reference, reference->width, reference->height));
        const auto check_image = o->hdr ? check_hdr_image : check_ldr_image;
        if (auto ok = check_image(*reference, "--reference " + o->reference); !ok)
            return report_error(ok.error().message);
        if (auto ok = check_image(*test, "--test " + o->test); !ok) return report_error(ok.error().message);
        const char* space = input_space == InputSpace::srgb     ? ", every input decoded from sRGB"
                            : input_space == InputSpace::linear ? ", every input taken as linear"
                                                                : "";
        const std::uint32_t w = reference->width, h = reference->height;
        const std::uint64_t pixels = std::uint64_t(w) * h;
        // The CPU's HDR-FLIP holds two tone-mapped copies and the exposure map besides LDR-FLIP's
        // planes; the device holds its planes in device memory (system memory on lavapipe), and
        // the maps come back as two more planes.
        const std::uint64_t needed =
            o->cpu ? ldr_flip_bytes(w, h) + image_bytes(w, h) * (o->hdr ? 3 : 1) + (o->hdr ? pixels * sizeof(float) : 0)
                   : DeviceFlip::bytes(w, h) + 2 * pixels * sizeof(float);
        if (auto ok = check_memory(
                fmt::format("--reference {}: {}-FLIP of {}x{}", o->reference, o->hdr ? "HDR" : "LDR", w, h), needed);
            !ok)
            return report_error(ok.error().message);

        const ExposureOptions& exposure = o->exposure;
        const bool read_maps = !o->out.empty() || !o->exposure_map.empty();
        const auto setup_start = std::chrono::steady_clock::now();
        const double setup_cpu_start = process_cpu_seconds();
        std::unique_ptr<Context> context;
        std::unique_ptr<DeviceFlip> device;
        if (!o->cpu) {
            auto created = Context::create({o->device, o->validation});
            if (!created) return report_error(created.error().message);
            context = std::move(*created);
            auto flip = DeviceFlip::create(*context, pixels_per_degree, w, h);
            if (!flip)
                return report_error(fmt::format("--reference {}: {} (--cpu computes FLIP on the CPU instead)",
                                                o->reference, flip.error().message));
            device = std::move(*flip);
        }
        const double setup_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count(),
                     setup_cpu = process_cpu_seconds() - setup_cpu_start;
        // One evaluation on the device or the CPU; the CPU code computes the maps in any case.
        auto evaluate = [&]() -> Result<FlipResult> {
            FlipResult r;
            if (o->hdr) {
                auto maps = device ? device->hdr(*reference, *test, exposure, read_maps)
                                   : HdrFlip(pixels_per_degree).maps(*reference, *test, exposure);
                if (!maps) return std::unexpected(maps.error());
                r.mean = maps->mean;
                r.range = maps->range;
                r.map = std::move(maps->error);
                r.exposure_map = std::move(maps->exposure);
            } else if (device && !read_maps) {
                auto mean = device->mean(*reference, *test);
                if (!mean) return std::unexpected(mean.error());
                r.mean = *mean;
            } else {
                Result<std::vector<float>> map = std::vector<float>{};
                if (device) {
                    auto terms = device->terms(*reference, *test);
                    if (!terms) return std::unexpected(terms.error());
                    map = std::move(terms->error);
                } else {
                    map = LdrFlip(pixels_per_degree).error_map(*reference, *test);
                }
                if (!map) return std::unexpected(map.error());
                r.mean = mean_error(*map);
                r.map = std::move(*map);
            }
            return r;
        };
        auto result = evaluate();
        if (!result) return report_error(fmt::format("--reference {}: {}", o->reference, result.error().message));
        std::vector<double> wall_s, cpu_s;
        for (int i = 0; i < o->timing; ++i) {
            const auto wall_start = std::chrono::steady_clock::now();
            const double cpu_start = process_cpu_seconds();
            if (auto again = evaluate(); !again)
                return report_error(fmt::format("--reference {}: {}", o->reference, again.error().message));
            wall_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
            cpu_s.push_back(process_cpu_seconds() - cpu_start);
        }
        if (context) report_validation_messages(*context);

        const std::string where = context ? "on " + context->device_name() : "on the CPU";
        if (o->hdr)
            std::cout << fmt::format("HDR-FLIP mean {} at {:.4g} pixels per degree ({}x{}{}; {} tone mapper, {} "
                                     "exposure{} from {:.4g} to {:.4g}) {}\n",
                                     result->mean, pixels_per_degree, w, h, space, to_string(exposure.tone_mapper),
                                     result->range.count, result->range.count == 1 ? "" : "s", result->range.start,
                                     result->range.stop, where);
        else
            std::cout << fmt::format("LDR-FLIP mean {} at {:.4g} pixels per degree ({}x{}{}) {}\n", result->mean,
                                     pixels_per_degree, w, h, space, where);
        if (o->timing)
            std::cout << fmt::format("timing: median of {} evaluation{}: {:.4f} s wall, {:.4f} CPU s; set-up {:.3f} s "
                                     "wall, {:.3f} CPU s\n",
                                     o->timing, o->timing == 1 ? "" : "s", median(wall_s), median(cpu_s), setup_wall,
                                     setup_cpu);
        const std::vector<float>&map = result->map, &exposure_map = result->exposure_map;

        // The maps as one set of files: both or neither.
        auto picture = [&](const std::vector<float>& values, const std::string& path) {
            const bool magma = extension_of(path) == ".png";
            auto image = std::make_shared<Image>(w, h);
            if (magma)
                *image = flip::magma_image(values, w, h);
            else
                for (std::size_t i = 0; i < values.size(); ++i)
                    image->pixels[i] = glm::vec4(glm::vec3(values[i]), 1.0f);
            return image_writer(path, std::move(image));
        };
        std::vector<OutputWriter> files;
        if (!o->out.empty()) files.push_back(picture(map, o->out));
        if (!o->exposure_map.empty()) files.push_back(picture(exposure_map, o->exposure_map));
        if (files.empty()) return 0;
        if (auto ok = write_atomically(files); !ok) return report_error(ok.error().message);
        for (const std::string& path : {o->out, o->exposure_map})
            if (!path.empty()) std::cout << fmt::format("wrote {}\n", terminal_text(path));
        return 0;
    };
}

} // namespace kdop::cli
