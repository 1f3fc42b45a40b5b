#include "temporal/metrics.h"

#include "harness/statistics.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>

namespace kdop {
namespace {

// A frame as PSNR sees it: LDR as it is in the store (no copy; valid while the computation runs,
// which changes no slot), HDR tone mapped at exposure 0 (what the pictures show) into `mapped`.
Result<const Image*> as_shown(const MetricFrame& f, FrameHandle handle, Image& mapped) {
    auto image = f.flip.store().image(handle);
    if (!image || f.range == ColorRange::ldr) return image;
    mapped = HdrFlip::tone_mapped(**image, f.flip.exposures().tone_mapper, 0.0f);
    return &mapped;
}

Result<FlipFigure> flip_figure(const MetricFrame& f, FrameHandle reference) {
    return f.flip.evaluate(reference, f.output, f.range, f.map);
}

// The frames `handles` name as PSNR sees them, in order.
template <std::size_t N>
Result<std::array<const Image*, N>> shown_frames(const MetricFrame& f, const FrameHandle (&handles)[N],
                                                 std::array<Image, N>& mapped) {
    std::array<const Image*, N> shown{};
    for (std::size_t i = 0; i < N; ++i) {
        auto image = as_shown(f, handles[i], mapped[i]);
        if (!image) return std::unexpected(image.error());
        shown[i] = *image;
    }
    return shown;
}

Result<FlipFigure> psnr_figure(const MetricFrame& f) {
    std::array<Image, 2> mapped;
    auto shown = shown_frames(f, {f.truth, f.output}, mapped);
    if (!shown) return std::unexpected(shown.error());
    return FlipFigure{psnr(*(*shown)[0], *(*shown)[1]), {}, {}};
}

Result<FlipFigure> temporal_psnr_figure(const MetricFrame& f) {
    std::array<Image, 4> mapped;
    auto shown = shown_frames(f, {f.previous_truth, f.truth, f.previous_output, f.output}, mapped);
    if (!shown) return std::unexpected(shown.error());
    const auto& [truth_before, truth, output_before, output] = *shown;
    return FlipFigure{temporal_psnr(*truth_before, *truth, *output_before, *output), {}, {}};
}

// 10 log10(1 / MSE) over `sum` of squared errors of `n` values.
double psnr_of(double sum, std::size_t n) { return sum == 0 ? INFINITY : 10.0 * std::log10(double(n) / sum); }

} // namespace

Metrics default_metrics() {
    Metrics m(kBuiltinMetrics);
    m[kShimmer] = {.name = "shimmer",
                   .unit = "FLIP",
                   .description = "FLIP between successive outputs",
                   .compares = Compared::previous,
                   .role = MetricRole::shimmer,
                   .flip = true,
                   .compute = [](const MetricFrame& f) { return flip_figure(f, f.previous_output); }};
    m[kGhosting] = {.name = "ghosting",
                    .unit = "FLIP",
                    .description = "FLIP against each frame's truth",
                    .compares = Compared::truth,
                    .role = MetricRole::ghosting,
                    .flip = true,
                    .compute = [](const MetricFrame& f) { return flip_figure(f, f.truth); }};
    m[kPsnr] = {.name = "psnr",
                .unit = "dB",
                .description = "PSNR against each frame's reference",
                .compares = Compared::truth,
                .role = MetricRole::ghosting,
                .needs_reference = true,
                .higher_is_better = true,
                .measured = false,
                .digits = 2,
                .compute = psnr_figure};
    m[kTpsnr] = {.name = "tpsnr",
                 .unit = "dB",
                 .description = "PSNR of the output's change against the reference's",
                 .compares = Compared::change,
                 .role = MetricRole::ghosting,
                 .needs_reference = true,
                 .higher_is_better = true,
                 .measured = false,
                 .digits = 2,
                 .compute = temporal_psnr_figure};
    return m;
}

std::string metric_names(const Metrics& metrics) {
    std::vector<std::string> names;
    for (const Metric& m : metrics) names.push_back(m.name);
    return fmt::format("{}", fmt::join(names, ", "));
}

Result<Metrics> metrics_named(std::span<const std::string> names) {
    Metrics metrics = default_metrics();
    for (Metric& m : metrics) m.measured = false;
    for (const std::string& name : names) {
        auto it = std::find_if(metrics.begin(), metrics.end(), [&](const Metric& m) { return m.name == name; });
        if (it == metrics.end())
            return usage_fail(fmt::format("no metric '{}'; kdop measures {}", name, metric_names(metrics)));
        it->measured = true;
    }
    // What report.md and report.html rank the variants by, and the pictures and viewer choose
    // their frames by.
    if (!metrics[kGhosting].measured)
        return usage_fail(
            fmt::format("ghosting is what kdop ranks variants by; give it beside {}", fmt::join(names, ", ")));
    return metrics;
}

std::vector<std::size_t> ranking_first(const Metrics& metrics) {
    std::vector<std::size_t> order;
    if (kGhosting < metrics.size()) order.push_back(kGhosting);
    for (std::size_t m = 0; m < metrics.size(); ++m)
        if (m != kGhosting) order.push_back(m);
    return order;
}

bool measured_on(const Metric& metric, SequenceRoles roles, bool has_reference) {
    const bool role = metric.role == MetricRole::ghosting ? roles.ghosting : roles.shimmer;
    return metric.measured && role && (has_reference || !metric.needs_reference);
}

MetricSummary summarize(std::span<const FrameFigures> frames, std::size_t metric, bool higher_is_better) {
    MetricSummary out;
    std::vector<double> values;
    double sum = 0;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const double v = frames[i].value(metric);
        if (std::isnan(v)) continue;
        sum += v;
        values.push_back(v);
        const double worst = out.worst ? frames[*out.worst].value(metric) : v;
        if (!out.worst || (higher_is_better ? v < worst : v > worst)) out.worst = i;
    }
    if (values.empty()) return out;
    out.mean = sum / double(values.size());
    std::sort(values.begin(), values.end());
    out.median = quantile_of_sorted(values, 0.5);
    out.p95 = quantile_of_sorted(values, 0.95);
    return out;
}

double psnr(const Image& reference, const Image& test) {
    double sum = 0;
    for (std::size_t i = 0; i < reference.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = double(test.pixels[i][c]) - double(reference.pixels[i][c]);
            sum += d * d;
        }
    return psnr_of(sum, 3 * reference.pixels.size());
}

double temporal_psnr(const Image& reference_before, const Image& reference, const Image& test_before,
                     const Image& test) {
    double sum = 0;
    for (std::size_t i = 0; i < reference.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = (double(test.pixels[i][c]) - double(test_before.pixels[i][c])) -
                             (double(reference.pixels[i][c]) - double(reference_before.pixels[i][c]));
            sum += d * d;
        }
    return psnr_of(sum, 3 * reference.pixels.size());
}

} // namespace kdop
