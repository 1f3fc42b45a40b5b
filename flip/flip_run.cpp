#include "flip/flip_run.h"

#include "core/input_files.h"
#include "core/memory_budget.h"
#include "core/write_files.h"
#include "flip/device_flip.h"
#include "flip/flip.h"
#include "flip/magma.h"
#include "images/image_io.h"

#include <fmt/format.h>

#include <sys/resource.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <memory>

namespace kdop {
namespace {

// One evaluation: the mean, and the maps when a file wants them.
struct Evaluated {
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

// A map file's extension, in lowercase: .exr or .png.
std::string lowercase_extension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::ranges::transform(extension, extension.begin(), [](unsigned char c) { return std::tolower(c); });
    return extension;
}

} // namespace

Result<FlipRunResult> run_flip(const FlipRunOptions& o) {
    if (auto ok = check_pixels_per_degree(o.ppd); !ok) return usage_fail("--ppd: " + ok.error().message);
    // A map's file: .exr for its values, .png in magma colors; checked before any work.
    const std::filesystem::path inputs[] = {o.reference, o.test};
    auto check_map_file = [&](const std::string& path, const char* option) -> Result<void> {
        if (path.empty()) return {};
        const std::string extension = lowercase_extension(path);
        if (extension != ".exr" && extension != ".png")
            return usage_fail(fmt::format("{}: {}: the map is written as .exr (its values) or .png (in magma "
                                          "colors)",
                                          option, path));
        if (auto ok = check_output_file(path, option); !ok) return usage_fail(ok.error().message);
        if (auto ok = check_not_an_input(path, option, inputs); !ok) return fail(ok.error().message);
        return {};
    };
    if (auto ok = check_map_file(o.out, "--out"); !ok) return std::unexpected(ok.error());
    if (auto ok = check_map_file(o.exposure_map, "--exposure-map"); !ok) return std::unexpected(ok.error());
    if (!o.out.empty() && o.out == o.exposure_map)
        return usage_fail(fmt::format("--out and --exposure-map both name {}", o.out));

    const InputSpace input_space = o.input_space;
    auto reference = read_image(o.reference, 0, input_space);
    if (!reference) return fail(reference.error().message);
    auto test = read_image(o.test, 0, input_space);
    if (!test) return fail(test.error().message);
    if (test->width != reference->width || test->height != reference->height)
        return fail(fmt::format("--test {}: {}x{}, but --reference {} is {}x{}", o.test, test->width, test->height,
                                o.reference, reference->width, reference->height));
    const auto check_image = o.hdr ? check_hdr_image : check_ldr_image;
    if (auto ok = check_image(*reference, "--reference " + o.reference); !ok) return fail(ok.error().message);
    if (auto ok = check_image(*test, "--test " + o.test); !ok) return fail(ok.error().message);
    const char* space = input_space == InputSpace::srgb     ? ", every input decoded from sRGB"
                        : input_space == InputSpace::linear ? ", every input taken as linear"
                                                            : "";
    const std::uint32_t w = reference->width, h = reference->height;
    const std::uint64_t pixels = std::uint64_t(w) * h;
    // The CPU's HDR-FLIP holds two tone-mapped copies and the exposure map besides LDR-FLIP's
    // planes; the device holds its planes in device memory (system memory on lavapipe), and
    // the maps come back as two more planes.
    const std::uint64_t needed =
        o.cpu ? ldr_flip_bytes(w, h) + image_bytes(w, h) * (o.hdr ? 3 : 1) + (o.hdr ? pixels * sizeof(float) : 0)
              : DeviceFlip::bytes(w, h) + 2 * pixels * sizeof(float);
    if (auto ok = check_memory(
            fmt::format("--reference {}: {}-FLIP of {}x{}", o.reference, o.hdr ? "HDR" : "LDR", w, h), needed);
        !ok)
        return fail(ok.error().message);

    const ExposureOptions& exposure = o.exposure;
    const bool read_maps = !o.out.empty() || !o.exposure_map.empty();
    const auto setup_start = std::chrono::steady_clock::now();
    const double setup_cpu_start = process_cpu_seconds();
    std::unique_ptr<Context> context;
    std::unique_ptr<DeviceFlip> device;
    if (!o.cpu) {
        auto created = Context::create(o.device);
        if (!created) return fail(created.error().message);
        context = std::move(*created);
        auto flip = DeviceFlip::create(*context, o.ppd, w, h);
        if (!flip)
            return fail(fmt::format("--reference {}: {} (--cpu computes FLIP on the CPU instead)", o.reference,
                                    flip.error().message));
        device = std::move(*flip);
    }
    const double setup_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count(),
                 setup_cpu = process_cpu_seconds() - setup_cpu_start;
    // One evaluation on the device or the CPU; the CPU code computes the maps in any case.
    auto evaluate = [&]() -> Result<Evaluated> {
        Evaluated r;
        if (o.hdr) {
            auto maps = device ? device->hdr(*reference, *test, exposure, read_maps)
                               : HdrFlip(o.ppd).maps(*reference, *test, exposure);
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
                map = LdrFlip(o.ppd).error_map(*reference, *test);
            }
            if (!map) return std::unexpected(map.error());
            r.mean = mean_error(*map);
            r.map = std::move(*map);
        }
        return r;
    };
    auto result = evaluate();
    if (!result) return fail(fmt::format("--reference {}: {}", o.reference, result.error().message));
    std::vector<double> wall_s, cpu_s;
    for (int i = 0; i < o.timing; ++i) {
        const auto wall_start = std::chrono::steady_clock::now();
        const double cpu_start = process_cpu_seconds();
        if (auto again = evaluate(); !again)
            return fail(fmt::format("--reference {}: {}", o.reference, again.error().message));
        wall_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
        cpu_s.push_back(process_cpu_seconds() - cpu_start);
    }

    FlipRunResult out;
    out.mean = result->mean;
    out.range = result->range;
    out.width = w;
    out.height = h;
    out.space = space;
    out.device = context ? context->device_name() : "";
    out.wall_s = std::move(wall_s);
    out.cpu_s = std::move(cpu_s);
    out.setup_wall_s = setup_wall;
    out.setup_cpu_s = setup_cpu;
    if (context) out.validation_messages = context->validation_messages();
    out.map = std::move(result->map);
    out.exposure_map = std::move(result->exposure_map);
    return out;
}

Result<void> write_flip_maps(const FlipRunOptions& o, const FlipRunResult& r) {
    auto picture = [&](const std::vector<float>& values, const std::string& path) {
        auto image = std::make_shared<Image>(r.width, r.height);
        if (lowercase_extension(path) == ".png")
            *image = flip::magma_image(values, r.width, r.height);
        else
            for (std::size_t i = 0; i < values.size(); ++i) image->pixels[i] = glm::vec4(glm::vec3(values[i]), 1.0f);
        return image_writer(path, std::move(image));
    };
    std::vector<OutputWriter> files;
    if (!o.out.empty()) files.push_back(picture(r.map, o.out));
    if (!o.exposure_map.empty()) files.push_back(picture(r.exposure_map, o.exposure_map));
    if (files.empty()) return {};
    return write_atomically(files);
}

} // namespace kdop
