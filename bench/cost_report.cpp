#include "cost_report.h"

#include "bench_inputs.h"
#include "gnuplot.h"

#include <fmt/format.h>

#include <cmath>

namespace kdop::bench {
namespace {

std::string number(double value, int decimals) {
    return std::isfinite(value) ? fmt::format("{:.{}f}", value, decimals) : "–";
}

std::string ratio(double value, double base) {
    const double r = value / base;
    return std::isfinite(r) ? fmt::format("{:.2f}×", r) : "–";
}

bool is_clip(const CostRow& row) { return !row.axis_set.empty(); }

const CostRow* find_row(const BenchResult& result, std::string_view name) {
    for (const CostRow& row : result.rows)
        if (row.variant == name) return &row;
    return nullptr;
}

bool measured_callgrind(const BenchResult& result) {
    return !result.rows.empty() && std::isfinite(result.rows.front().instr_per_px);
}

std::string static_table(const BenchResult& result) {
    std::string out = "| variant | k | SPIR-V instructions | float ops | mul | add/sub | fma | min/max | div | cmp/sel | other "
                      "| loop form | vs loop | analytic min | vs min |\n";
    out += "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
    for (const CostRow& r : result.rows) {
        const FloatOps& f = r.float_ops;
        out += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", r.variant,
                           r.k ? std::to_string(r.k) : "–", r.spirv_instructions, f.total(), f.mul, f.add_sub, f.fma,
                           f.min_max, f.div, f.compare_select, f.other, number(r.baseline_float_ops, 0),
                           ratio(double(f.total()), r.baseline_float_ops), number(r.analytic_min_ops, 0),
                           ratio(double(f.total()), r.analytic_min_ops));
    }
    return out;
}

std::string measured_table(const BenchResult& result) {
    std::string out = "| variant | median ms | IQR ms | marginal ms | ms vs aabb | loop form ms | loop marginal ms "
                      "| instr/px | loop instr/px | vs loop |\n";
    out += "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
    for (const CostRow& r : result.rows) {
        const double loop_marginal = r.marginal_ms + (r.baseline_ms_median - r.ms_median);
        out += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", r.variant, number(r.ms_median, 2),
                           number(r.ms_spread, 2), number(r.marginal_ms, 2), number(r.ms_vs_aabb, 2),
                           number(r.baseline_ms_median, 2), number(loop_marginal, 2), number(r.instr_per_px, 1),
                           number(r.baseline_instr_per_px, 1), ratio(r.instr_per_px, r.baseline_instr_per_px));
    }
    return out;
}

// Hardened numerics (the default) against the paper's, per variant.
std::string hardening_table(const BenchResult& result) {
    std::string out = "| variant | float ops | paper | ratio | instr/px | paper | ratio | median ms | paper ms |\n"
                      "|---|--:|--:|--:|--:|--:|--:|--:|--:|\n";
    for (const CostRow& r : result.rows) {
        if (!std::isfinite(r.paper_float_ops)) continue;
        const double ops = double(r.float_ops.total());
        out += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", r.variant, ops, r.paper_float_ops,
                           ratio(ops, r.paper_float_ops), number(r.instr_per_px, 1), number(r.paper_instr_per_px, 1),
                           ratio(r.instr_per_px, r.paper_instr_per_px), number(r.ms_median, 2), number(r.paper_ms_median, 2));
    }
    return out;
}

std::string sweep_table(const BenchResult& result) {
    const SweepResult& s = result.sweep;
    std::string header = "| size | Mpixel |", rule = "|---|--:|";
    for (const std::string& k : s.kernels) {
        header += fmt::format(" {} ms |", k);
        rule += "--:|";
    }
    std::string out = header + "\n" + rule + "\n";
    for (std::size_t i = 0; i < s.sizes.size(); ++i) {
        const double mpixel = double(s.sizes[i].first) * s.sizes[i].second * 1e-6;
        out += fmt::format("| {}x{} | {:.2f} |", s.sizes[i].first, s.sizes[i].second, mpixel);
        for (double ms : s.ms_median[i]) out += fmt::format(" {:.2f} |", ms);
        out += "\n";
    }
    return out;
}

// The targets set for the cost work (issue 4), each evaluated on this run's numbers.
std::string targets(const BenchResult& result) {
    std::string out;
    auto line = [&](bool met, const std::string& text) { out += fmt::format("- **{}**: {}\n", met ? "met" : "missed", text); };
    if (const CostRow* dop32 = find_row(result, "dop32-clip-n9")) {
        const double r = double(dop32->float_ops.total()) / dop32->baseline_float_ops;
        line(r <= 0.55, fmt::format("dop32-clip-n9 at ≤ 0.55× the loop form's float ops: {} / {} = {:.3f}×",
                                    dop32->float_ops.total(), dop32->baseline_float_ops, r));
    }
    std::string over;
    double worst = 0;
    for (const CostRow& r : result.rows) {
        if (!is_clip(r)) continue;
        const double x = double(r.float_ops.total()) / r.analytic_min_ops;
        worst = std::max(worst, x);
        if (x > 1.05) over += fmt::format(" {} ({:.3f}×)", r.variant, x);
    }
    line(over.empty(), fmt::format("every variant within 5% of its analytic minimum: worst {:.3f}×{}", worst,
                                   over.empty() ? "" : "; over:" + over));
    if (measured_callgrind(result)) {
        std::string above, not_below;
        for (const CostRow& r : result.rows) {
            if (!is_clip(r)) continue;
            if (r.instr_per_px > r.baseline_instr_per_px) above += " " + r.variant;
            if (r.k >= 16 && !(r.instr_per_px < r.baseline_instr_per_px)) not_below += " " + r.variant;
        }
        line(above.empty(), "no variant's callgrind instructions per pixel above its loop form's" +
                                (above.empty() ? std::string() : "; above:" + above));
        line(not_below.empty(), "16-, 22- and 32-DOP strictly below their loop forms" +
                                    (not_below.empty() ? std::string() : "; not below:" + not_below));
        if (const CostRow* dop32 = find_row(result, "dop32-clip-n9"); dop32 && find_row(result, "gather-n9")) {
            const double gather = find_row(result, "gather-n9")->instr_per_px;
            out += fmt::format("- dop32-clip-n9's marginal cost over the gather, in instructions per pixel: {:.1f} against "
                               "the loop form's {:.1f} ({:.2f}×)\n",
                               dop32->instr_per_px - gather, dop32->baseline_instr_per_px - gather,
                               (dop32->instr_per_px - gather) / (dop32->baseline_instr_per_px - gather));
        }
    }
    return out;
}

constexpr const char* kDerivation = R"(The fewest scalar float operations kdop's formulation needs, from each axis's
nonzero components (`generator/analytic_cost.h`; a multiply-add counts 1, as in the float-op count).
Per slab, for an axis with m nonzero components and N neighborhood colors (the pixel's own among them):

| part | clip | varclip | why |
|---|---|---|---|
| projections | (N + 1)(m − 1) | (N + 1)(m − 1) | the N colors and the ray direction; the axis is scaled so one component is exactly 1, so a projection is m − 1 multiply-adds; the pixel's projection is the ray origin's |
| extent | 2(N − 1) | 2N + 9 | min and max of N values; for varclip: the mean (N − 1 adds, a scale), the second moment (N multiply-adds), the variance (a scale, a multiply-add, a scale), its clamp at 0 and sqrt (2), mean ∓ γσ (2), widening to contain the origin (2) |
| dilation | 2 | 2 | lo − padding · scale, hi + padding · scale (a multiply-add each) |
| exit | 6 | 5 | reciprocal of the direction's projection, compare and select of the plane the ray heads for, minus the origin (clip only), times the reciprocal, min into t |

Per pixel: the ray direction (3); the padding scale, max(1, |current| channels) (6); whether the history
is usable, |dir|₁ + |current|₁ ≤ FLT_MAX (9); current + max(t, 0) · dir (4). For varclip also −γ (1),
its power-of-two-scaled frame (10) and the N colors relative to current (3N multiply-adds).

The emitted clips spend exactly 2 operations per slab more than this (a test holds them to it): their running
min and max start from ±FLT_MAX. The formulation does not need those, but with them lavapipe's
compiled code drops its NaN handling down the chain, which measured about 8% fewer instructions per pixel
for dop32 than starting from the first projection.)";

std::string run_ms(double ms, double pixels) { return fmt::format("{:.2f} ms ({:.1f} ns/pixel)", ms, ms * 1e6 / pixels); }

constexpr const char* kChartStyle = R"(set terminal pngcairo size 1400,560 font "sans,10"
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.85 border -1
set boxwidth 0.9
set grid ytics
set key top left
set xtics rotate by -40 scale 0
set yrange [0:*]
set rmargin 10
)";

} // namespace

std::vector<std::string> cost_chart_names(const BenchResult& result) {
    std::vector<std::string> names{"static_cost.png", "measured_cost.png"};
    if (!result.sweep.sizes.empty()) names.push_back("size_sweep.png");
    return names;
}

std::string cost_report_markdown(const BenchResult& result, const ReportContext& c) {
    const BenchOptions& o = c.options;
    const double timing_pixels = double(o.timing_size.first) * o.timing_size.second;
    std::string out = "# kdop cost bench\n\n";
    out += fmt::format("- date: {}\n- commit: {}\n- machine: {}\n- device: {}\n- driver: {}\n- command: `{}`\n", c.date, c.commit,
                       c.machine, result.device_name, result.driver_info, c.command);
    out += fmt::format("- content: current = grass texture (seed {}), history = asphalt texture (seed {}), so every "
                       "pixel is clipped\n\n",
                       kCurrentSeed, kHistorySeed);
    const auto charts = cost_chart_names(result);
    out += "## Targets\n\n" + targets(result) + "\n";
    out += fmt::format("![Float operations per variant against the loop form and the analytic minimum]({})\n\n", charts[0]);
    out += fmt::format("![Measured cost on the device: callgrind instructions per pixel and marginal time]({})\n\n",
                       charts[1]);

    out += "## Static cost\n\nFrom the optimized SPIR-V that ships (`generator/spirv_cost.h`): scalar float operations, vector "
           "operations once per component, `OpDot` of N as 2N − 1, `Fma` as 1. The loop form is the supplement's listing, "
           "compiled and optimized the same way.\n\n";
    out += static_table(result) + "\n";
    out += "### The analytic minimum\n\n" + std::string(kDerivation) + "\n\n";

    out += fmt::format("## Measured cost\n\n{} rounds at {}x{}; every round dispatches each kernel once, in an order "
                       "rotated round to round. Times are {}; median and interquartile range (IQR). Marginal = the "
                       "variant minus the gather-only kernel of its neighborhood (same loads and store, no clip).\n\n",
                       o.rounds, o.timing_size.first, o.timing_size.second,
                       result.device_clock ? "GPU timestamps around the dispatch" : "submit-to-fence wall times");
    if (o.callgrind)
        out += fmt::format("instr/px: CPU instructions lavapipe executes per pixel for one {0}x{0} dispatch, counted by "
                           "callgrind around the dispatch alone (`LP_NUM_THREADS=0`, `bench/kdop-dispatch-probe`). It "
                           "repeats from run to run, so it is the number to compare where times are noisy.\n\n",
                           o.callgrind_size);
    out += measured_table(result) + "\n";
    if (const CostRow* gather = find_row(result, "gather-n9"); gather && std::isfinite(gather->ms_median))
        out += fmt::format("gather-n9 alone: {}; copy: {}.\n\n", run_ms(gather->ms_median, timing_pixels),
                           run_ms(find_row(result, "copy")->ms_median, timing_pixels));

    out += "## Cost of hardening\n\nThe default variants against the same variants with the paper's numerics "
           "(`kdop gen --numerics paper`), which `kdop stress` shows returning NaN or colors outside the k-DOP on "
           "extreme input. Both were timed in the same interleaved rounds and counted by callgrind alike.\n\n";
    out += hardening_table(result) + "\n";

    if (!result.sweep.sizes.empty()) {
        out += fmt::format("## Size sweep\n\nMedian of {} interleaved rounds per size.\n\n", o.sweep_rounds);
        out += sweep_table(result) + "\n";
        out += fmt::format("![Time against pixel count]({})\n\n", charts[2]);
    }
    return out;
}

Result<std::vector<OutputFile>> cost_charts(const BenchResult& result, const std::filesystem::path& scratch,
                                            const std::filesystem::path& out_dir) {
    const auto names = cost_chart_names(result);
    std::vector<std::vector<std::string>> clips;
    for (const CostRow& r : result.rows) {
        if (!is_clip(r)) continue;
        const double loop_marginal = r.marginal_ms + (r.baseline_ms_median - r.ms_median);
        std::vector<std::string> row{r.variant};
        for (double v : {double(r.float_ops.total()), r.analytic_min_ops, r.baseline_float_ops, r.instr_per_px,
                         r.baseline_instr_per_px, r.marginal_ms, loop_marginal})
            row.push_back(gnuplot_number(v));
        clips.push_back(std::move(row));
    }
    if (auto ok = write_text(scratch / "clips.dat", gnuplot_data(clips)); !ok) return std::unexpected(ok.error());
    const CostRow* gather = find_row(result, "gather-n9");

    std::string script = kChartStyle;
    script += fmt::format("set output '{}'\n", (scratch / names[0]).string());
    script += "set title 'Static cost: scalar float operations per pixel (optimized SPIR-V)'\nset ylabel 'float ops'\n";
    script += fmt::format("plot '{0}' using 2:xtic(1) title 'emitted (kdop)', '' using 3 title 'analytic minimum', "
                          "'' using 4 title 'loop form (supplement)'\n",
                          (scratch / "clips.dat").string());
    // Measured cost: callgrind's instructions (when counted) above the marginal time.
    const bool counted = measured_callgrind(result);
    script += fmt::format("set output '{}'\nset terminal pngcairo size 1400,{} font 'sans,10'\nset multiplot layout {},1\n",
                          (scratch / names[1]).string(), counted ? 1000 : 560, counted ? 2 : 1);
    if (counted) {
        script += fmt::format("set title 'lavapipe: CPU instructions per pixel of one dispatch (callgrind)'\n"
                              "set ylabel 'instructions / pixel'\n");
        script += fmt::format("plot '{0}' using 5:xtic(1) title 'emitted (kdop)', '' using 6 title 'loop form'{1}\n",
                              (scratch / "clips.dat").string(),
                              gather ? fmt::format(", {} with lines dt 2 lw 2 lc rgb 'black' title 'gather-n9 alone'",
                                                   gnuplot_number(gather->instr_per_px))
                                     : "");
    }
    script += fmt::format("set title '{}: marginal time over the gather-only kernel (median)'\nset ylabel 'ms'\n"
                          "set yrange [*:*]\n",
                          result.device_name);
    script += fmt::format("plot '{0}' using 7:xtic(1) title 'emitted (kdop)', '' using 8 title 'loop form'\n"
                          "unset multiplot\n",
                          (scratch / "clips.dat").string());

    if (!result.sweep.sizes.empty()) {
        const SweepResult& s = result.sweep;
        std::vector<std::vector<std::string>> sweep;
        for (std::size_t i = 0; i < s.sizes.size(); ++i) {
            std::vector<std::string> row{gnuplot_number(double(s.sizes[i].first) * s.sizes[i].second * 1e-6)};
            for (double ms : s.ms_median[i]) row.push_back(gnuplot_number(ms));
            sweep.push_back(row);
        }
        if (auto ok = write_text(scratch / "sweep.dat", gnuplot_data(sweep)); !ok) return std::unexpected(ok.error());
        script += fmt::format("set terminal pngcairo size 1000,700 font 'sans,10'\nset output '{}'\n",
                              (scratch / names[2]).string());
        script += "set style data linespoints\nset logscale xy\nset xtics rotate by 0 scale 1\nset yrange [*:*]\n"
                  "set xlabel 'Mpixel'\nset ylabel 'ms (median)'\nset title 'Dispatch time against pixel count'\n";
        script += "plot ";
        for (std::size_t k = 0; k < s.kernels.size(); ++k)
            script += fmt::format("{}'{}' using 1:{} title '{}'", k ? ", " : "", (scratch / "sweep.dat").string(), k + 2,
                                  s.kernels[k]);
        script += "\n";
    }
    return draw_charts(script, names, scratch, out_dir);
}

} // namespace kdop::bench
