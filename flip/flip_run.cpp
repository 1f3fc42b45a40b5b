#include "flip/flip_run.h"

#include "core/memory_budget.h"
#include "core/write_files.h"
#include "flip/device_flip.h"
#include "flip/flip.h"
#include "flip/flip_check.h"
#include "flip/magma.h"
#include "harness/declared_table.h"
#include "harness/gnuplot.h"
#include "harness/scratch_directory.h"
#include "harness/subprocess.h"
#include "images/image_io.h"

#include <fmt/format.h>

#include <sys/resource.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>

namespace kdop {
namespace {

// One evaluation: the mean and the maps.
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

// The statistics of every test as a table: the CSV --csv writes.
Table statistics_table(const std::vector<FlipTestResult>& tests) {
    using Row = FlipTestResult;
    auto figure = [](double FlipStatistics::*f) { return [f](const Row& r) { return Value(r.statistics.*f); }; };
    const DeclaredColumns<Row> columns{
        {{"test", "", Shown::text}, [](const Row& r) { return Value(r.test); }},
        {{"mean", "FLIP", Shown::fixed, 6}, figure(&FlipStatistics::mean)},
        {{"weighted_median", "FLIP", Shown::fixed, 6}, figure(&FlipStatistics::weighted_median)},
        {{"weighted_q1", "FLIP", Shown::fixed, 6}, figure(&FlipStatistics::weighted_q1)},
        {{"weighted_q3", "FLIP", Shown::fixed, 6}, figure(&FlipStatistics::weighted_q3)},
        {{"median", "FLIP", Shown::fixed, 6}, figure(&FlipStatistics::median)},
        {{"q1", "FLIP", Shown::fixed, 6}, figure(&FlipStatistics::q1)},
        {{"q3", "FLIP", Shown::fixed, 6}, figure(&FlipStatistics::q3)},
        {{"min", "FLIP", Shown::fixed, 6}, figure(&FlipStatistics::min)},
        {{"max", "FLIP", Shown::fixed, 6}, figure(&FlipStatistics::max)},
    };
    return declared_table<Row>(columns, tests);
}

// Every test's weighted histogram (NVlabs/flip's: each bucket's count times its center, per
// megapixel), one line each, with its mean and weighted median in the key.
Result<OutputFile> histogram_chart(const std::vector<FlipTestResult>& tests, std::uint32_t width, std::uint32_t height,
                                   const std::filesystem::path& to) {
    ScratchDirectory scratch("kdop-flip");
    if (scratch.path.empty()) return fail("no scratch directory for the histogram");
    const double megapixels = double(width) * double(height) / (1024.0 * 1024.0);
    std::string plot;
    for (std::size_t t = 0; t < tests.size(); ++t) {
        std::vector<std::vector<std::string>> rows;
        const std::size_t buckets = tests[t].histogram.size();
        for (std::size_t b = 0; b < buckets; ++b) {
            const double center = (double(b) + 0.5) / double(buckets);
            rows.push_back(
                {gnuplot_number(center), gnuplot_number(double(tests[t].histogram[b]) * center / megapixels)});
        }
        const std::filesystem::path data = scratch.path / fmt::format("test-{}.dat", t);
        if (auto ok = write_text(data, gnuplot_data(rows)); !ok) return std::unexpected(ok.error());
        const std::string title = fmt::format("{}: mean {:.4f}, weighted median {:.4f}",
                                              std::filesystem::path(tests[t].test).filename().string(),
                                              tests[t].statistics.mean, tests[t].statistics.weighted_median);
        plot += fmt::format("{}{} using 1:2 with histeps lw 2 title {}", plot.empty() ? "" : ", ",
                            gnuplot_string(data.string()), gnuplot_string(title));
    }
    const std::string script = gnuplot_terminal(1000, 600) + gnuplot_output(scratch.path, 0) +
                               fmt::format("set grid\nset key top right\n"
                                           "set title 'Weighted FLIP histogram ({} buckets): the pixels of each bucket "
                                           "times its error, per megapixel'\n"
                                           "set xlabel 'FLIP error'\nset ylabel 'weighted FLIP sum per megapixel'\nset "
                                           "xrange [0:1]\nset yrange [0:*]\n"
                                           "plot {}\n",
                                           kFlipHistogramBuckets, plot);
    auto drawn = draw_charts(script, {"histogram.png"}, scratch.path, to.parent_path());
    if (!drawn) return std::unexpected(drawn.error());
    OutputFile chart = std::move(drawn->front());
    chart.path = to;
    return chart;
}

// How the inputs are decoded, as a clause of the summary line, or empty.
const char* input_space_clause(InputSpace space) {
    return space == InputSpace::srgb     ? ", every input decoded from sRGB"
           : space == InputSpace::linear ? ", every input taken as linear"
                                         : "";
}

// Fails unless `image` is what the run's FLIP takes (LDR: RGB in [0, 1]; HDR: from 0 up).
Result<void> check_input(const FlipRunOptions& o, const Image& image, const std::string& what) {
    return o.hdr ? check_hdr_image(image, what) : check_ldr_image(image, what);
}

// The reference, read and checked, and the memory its evaluations take checked against the budget.
Result<Image> read_reference(const FlipRunOptions& o) {
    auto reference = read_image(o.reference, 0, o.input_space);
    if (!reference) return fail(reference.error().message);
    if (auto ok = check_input(o, *reference, "--reference " + o.reference); !ok) return fail(ok.error().message);
    const std::uint32_t w = reference->width, h = reference->height;
    const std::uint64_t pixels = std::uint64_t(w) * h;
    // The CPU's HDR-FLIP holds two tone-mapped copies and the exposure map besides LDR-FLIP's
    // planes; the device holds its planes in device memory (system memory on lavapipe), and
    // the maps come back as two more planes; the statistics sort a copy of the map in doubles.
    const std::uint64_t needed =
        (o.cpu ? ldr_flip_bytes(w, h) + image_bytes(w, h) * (o.hdr ? 3 : 1) + (o.hdr ? pixels * sizeof(float) : 0)
               : DeviceFlip::bytes(w, h) + 2 * pixels * sizeof(float)) +
        image_bytes(w, h) + 2 * pixels * sizeof(double);
    if (auto ok = check_memory(
            fmt::format("--reference {}: {}-FLIP of {}x{}", o.reference, o.hdr ? "HDR" : "LDR", w, h), needed);
        !ok)
        return fail(ok.error().message);
    return std::move(*reference);
}

// Where FLIP is computed: the device's passes for the reference's size, or (--cpu) none, the CPU's
// reference code; and what setting them up took.
struct FlipBackend {
    std::unique_ptr<Context> context;
    std::unique_ptr<DeviceFlip> device; // null: on the CPU
    double setup_wall_s = 0, setup_cpu_s = 0;
};

Result<FlipBackend> create_backend(const FlipRunOptions& o, std::uint32_t width, std::uint32_t height) {
    FlipBackend backend;
    const auto setup_start = std::chrono::steady_clock::now();
    const double setup_cpu_start = process_cpu_seconds();
    if (!o.cpu) {
        auto created = Context::create(o.device);
        if (!created) return fail(created.error().message);
        backend.context = std::move(*created);
        auto flip = DeviceFlip::create(*backend.context, o.ppd, width, height);
        if (!flip)
            return fail(fmt::format("--reference {}: {} (--cpu computes FLIP on the CPU instead)", o.reference,
                                    flip.error().message));
        backend.device = std::move(*flip);
    }
    backend.setup_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count();
    backend.setup_cpu_s = process_cpu_seconds() - setup_cpu_start;
    return backend;
}

// HDR-FLIP of `test`, on the device or the CPU, with its maps.
Result<Evaluated> evaluate_hdr(const FlipRunOptions& o, DeviceFlip* device, const Image& reference, const Image& test,
                               bool maps) {
    auto hdr =
        device ? device->hdr(reference, test, o.exposure, maps) : HdrFlip(o.ppd).maps(reference, test, o.exposure);
    if (!hdr) return std::unexpected(hdr.error());
    Evaluated r;
    r.mean = hdr->mean;
    r.range = hdr->range;
    r.map = std::move(hdr->error);
    r.exposure_map = std::move(hdr->exposure);
    return r;
}

// One evaluation on the device or the CPU: with `maps`, its error map read back for the
// statistics; without, the mean alone, as a measurement computes it (what --timing times).
Result<Evaluated> evaluate(const FlipRunOptions& o, DeviceFlip* device, const Image& reference, const Image& test,
                           bool maps) {
    if (o.hdr) return evaluate_hdr(o, device, reference, test, maps);
    Evaluated r;
    if (device && !maps) {
        auto mean = device->mean(reference, test);
        if (!mean) return std::unexpected(mean.error());
        r.mean = *mean;
        return r;
    }
    Result<std::vector<float>> map = std::vector<float>{};
    if (device) {
        auto terms = device->terms(reference, test);
        if (!terms) return std::unexpected(terms.error());
        map = std::move(terms->error);
    } else {
        map = LdrFlip(o.ppd).error_map(reference, test);
    }
    if (!map) return std::unexpected(map.error());
    r.mean = mean_error(*map);
    r.map = std::move(*map);
    return r;
}

// `o.timing` more evaluations of `test`, the mean alone, each one's wall and CPU seconds into `out`.
Result<void> time_evaluations(const FlipRunOptions& o, DeviceFlip* device, const Image& reference, const Image& test,
                              const std::string& path, FlipRunResult& out) {
    for (int i = 0; i < o.timing; ++i) {
        const auto wall_start = std::chrono::steady_clock::now();
        const double cpu_start = process_cpu_seconds();
        if (auto again = evaluate(o, device, reference, test, false); !again)
            return fail(fmt::format("--test {}: {}", path, again.error().message));
        out.wall_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
        out.cpu_s.push_back(process_cpu_seconds() - cpu_start);
    }
    return {};
}

// The test at `path` read, checked against the reference and evaluated into out.tests (the
// first one also timed); its maps kept where a file wants them (then it is the only test).
Result<void> measure_test(const FlipRunOptions& o, DeviceFlip* device, const Image& reference, const std::string& path,
                          FlipRunResult& out) {
    auto test = read_image(path, 0, o.input_space);
    if (!test) return fail(test.error().message);
    if (test->width != reference.width || test->height != reference.height)
        return fail(fmt::format("--test {}: {}x{}, but --reference {} is {}x{}", path, test->width, test->height,
                                o.reference, reference.width, reference.height));
    if (auto ok = check_input(o, *test, "--test " + path); !ok) return fail(ok.error().message);
    auto result = evaluate(o, device, reference, *test, true);
    if (!result) return fail(fmt::format("--test {}: {}", path, result.error().message));
    if (out.tests.empty())
        if (auto ok = time_evaluations(o, device, reference, *test, path, out); !ok) return ok;
    FlipTestResult& t = out.tests.emplace_back();
    t.test = path;
    t.statistics = flip_statistics(result->map);
    t.statistics.mean = result->mean; // as the evaluation summed it (HDR-FLIP's and the device's own order)
    t.histogram = flip_histogram(result->map);
    t.range = result->range;
    if (!o.out.empty() || !o.exposure_map.empty())
        t.map = std::move(result->map), t.exposure_map = std::move(result->exposure_map);
    return {};
}

// Whether FLIP runs on the CPU because the device it would run on is kdop's default, lavapipe:
// no --device, no $KDOP_DEVICE, no --validation (which asks for a device). Lavapipe runs the
// device passes on the same cores, slower than the CPU code (a 1080p LDR pair here: 1.92 CPU s
// against 1.15), and its instance alone costs start-up time.
bool cpu_by_default(const FlipRunOptions& o) {
    const char* named = std::getenv("KDOP_DEVICE");
    return !o.cpu && o.device.device.empty() && !o.device.validation && (!named || !*named);
}

} // namespace

Result<FlipRunResult> run_flip(const FlipRunOptions& given) {
    FlipRunOptions o = given;
    const bool by_default = cpu_by_default(given);
    o.cpu = o.cpu || by_default;
    if (check(o)) return fail("kdop flip: options that check() refuses");
    if (!o.histogram.empty() && find_program("gnuplot").empty())
        return fail(fmt::format("--histogram {}: it is drawn with gnuplot, which is not in PATH (Debian: gnuplot-nox)",
                                o.histogram));
    auto reference = read_reference(o);
    if (!reference) return std::unexpected(reference.error());
    auto backend = create_backend(o, reference->width, reference->height);
    if (!backend) return std::unexpected(backend.error());
    FlipRunResult out;
    out.cpu_by_default = by_default;
    for (const std::string& path : o.tests)
        if (auto ok = measure_test(o, backend->device.get(), *reference, path, out); !ok)
            return std::unexpected(ok.error());
    out.width = reference->width;
    out.height = reference->height;
    out.space = input_space_clause(o.input_space);
    out.device = backend->context ? backend->context->device_name() : "";
    out.setup_wall_s = backend->setup_wall_s;
    out.setup_cpu_s = backend->setup_cpu_s;
    if (backend->context) out.validation_messages = backend->context->validation_messages();
    return out;
}

Result<void> write_flip_outputs(const FlipRunOptions& o, const FlipRunResult& r) {
    auto picture = [&](const std::vector<float>& values, const std::string& path) {
        auto image = std::make_shared<Image>(r.width, r.height);
        if (lowercase_extension(path) == ".png")
            *image = flip::magma_image(values, r.width, r.height);
        else
            for (std::size_t i = 0; i < values.size(); ++i) image->pixels[i] = glm::vec4(glm::vec3(values[i]), 1.0f);
        return image_writer(path, std::move(image));
    };
    std::vector<OutputWriter> files;
    if (!o.out.empty()) files.push_back(picture(r.tests.front().map, o.out));
    if (!o.exposure_map.empty()) files.push_back(picture(r.tests.front().exposure_map, o.exposure_map));
    std::vector<OutputFile> contents; // the CSV and the chart, which their writers refer to
    contents.reserve(2);
    if (!o.csv.empty()) files.push_back(content_writer(contents.emplace_back(o.csv, statistics_table(r.tests).csv())));
    if (!o.histogram.empty()) {
        auto chart = histogram_chart(r.tests, r.width, r.height, o.histogram);
        if (!chart) return fail(fmt::format("--histogram {}: {}", o.histogram, chart.error().message));
        files.push_back(content_writer(contents.emplace_back(std::move(*chart))));
    }
    if (files.empty()) return {};
    return write_atomically(files);
}

} // namespace kdop
