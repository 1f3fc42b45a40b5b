#include "bench/cost_report.h"

#include "bench/bench_inputs.h"
#include "harness/gnuplot.h"

#include <fmt/format.h>

#include <cmath>

namespace kdop::bench {
namespace {

const char* const kStaticColumns[] = {"variant",
                                      "k",
                                      "spirv_instructions",
                                      "float_ops",
                                      "mul",
                                      "add_sub",
                                      "fma",
                                      "min_max",
                                      "div",
                                      "compare_select",
                                      "other_float",
                                      "loop_float_ops",
                                      "float_ops_vs_loop",
                                      "analytic_min_ops",
                                      "float_ops_vs_min"};
const char* const kMeasuredColumns[] = {"variant",
                                        "ms_median",
                                        "ms_q1",
                                        "ms_q3",
                                        "loop_ms_median",
                                        "vs_loop_ms_noise",
                                        "marginal_ms",
                                        "marginal_ms_noise",
                                        "ms_vs_aabb",
                                        "instr_per_px",
                                        "loop_instr_per_px",
                                        "instr_vs_loop",
                                        "marginal_instr_per_px"};
const char* const kHardeningColumns[] = {"variant",      "float_ops",          "paper_float_ops",
                                         "instr_per_px", "paper_instr_per_px", "instr_vs_paper",
                                         "ms_median",    "paper_ms_median"};

std::vector<std::string> names(std::span<const char* const> columns) { return {columns.begin(), columns.end()}; }

const CostRow* find_row(const BenchResult& result, const VariantKey& key) {
    for (const CostRow& row : result.rows)
        if (row.key == key) return &row;
    return nullptr;
}

bool measured_callgrind(const BenchResult& result) {
    return !result.rows.empty() && std::isfinite(result.rows.front().instr_per_px);
}

Table sweep_table(const SweepResult& s) {
    std::vector<Column> columns{{"size", "", Shown::text}, {"mpixel", "", Shown::fixed, 2, "Mpixel"}};
    for (const std::string& k : s.kernels) columns.push_back({k, "ms", Shown::fixed, 2});
    Table table(std::move(columns));
    for (std::size_t i = 0; i < s.sizes.size(); ++i) {
        std::vector<Value> row{fmt::format("{}x{}", s.sizes[i].first, s.sizes[i].second),
                               double(s.sizes[i].first) * s.sizes[i].second * 1e-6};
        for (double ms : s.ms_median[i]) row.push_back(ms);
        table.add(std::move(row));
    }
    return table;
}

constexpr const char* kDerivation = R"(A lower bound on the scalar float operations of kdop's hardened clip, from each
axis's nonzero components (`generator/analytic_cost.h`, where the derivation is; a multiply-add counts 1,
as in the float-op count; lavapipe has no fused multiply-add, so there each is two instructions). Each
slab spans the neighbors' extent, measured from the current color (which stands for the center pixel)
and then padded by 1e-5 per unit of axis length; the ray leaves through the plane it heads for. For an
axis with m nonzero components and N neighborhood colors, in whichever frame is cheaper:

| part | relative frame (colors − current) | absolute frame |
|---|---|---|
| per pixel | 18 + 3(N − 1) | 18 |
| clip slab | N(m − 1) + 2N + 3 | (N + 1)(m − 1) + 2N + 5 |
| varclip (always relative) | per pixel 18 + 3(N − 1) + 11, per slab N(m − 1) + 2N + 11 | |

Per pixel: the ray direction (3); whether the history is usable, |dir|₁ + |current|₁ ≤ FLT_MAX (12);
current + t · dir (3). Per clip slab: the projections of the N − 1 other neighbors and of the ray (and,
absolute, of the current color); min and max with the center; the padding (2); the exit (a select, a
division, a min). Two scaled components of one magnitude (YCoCg's Y and Cg) cost one multiply-add on
their sum, which axes with the same pair share. The emitted clips spend exactly this in their frame (a
test holds them to it), plus, in the absolute frame, 2 per slab for running min and max that start from
±FLT_MAX: with them lavapipe's compiled code drops its NaN handling down the chain.)";

std::string run_ms(double ms, double pixels) {
    return fmt::format("{:.2f} ms ({:.1f} ns/pixel)", ms, ms * 1e6 / pixels);
}

constexpr const char* kChartStyle = R"(set style data histograms
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

std::string cost_report_markdown(const BenchResult& result, const RunMetadata& run, const ReportSettings& settings) {
    const BenchOptions& o = settings.options;
    const Table table = cost_table(result.rows);
    const double timing_pixels = double(o.timing_size.first) * o.timing_size.second;
    const auto chart = [&](std::size_t i, const char* text) {
        return i < settings.charts.size() ? fmt::format("![{}]({})\n\n", text, settings.charts[i]) : std::string();
    };
    std::string out = "# kdop cost bench\n\n" + metadata_markdown(run);
    out += fmt::format("- content: current = grass texture (seed {}), history = asphalt texture (seed {}), so every "
                       "pixel is clipped\n\n",
                       kCurrentSeed, kHistorySeed);
    out += chart(0, "Float operations per variant against the loop form and the analytic lower bound");
    out += chart(1, "Measured cost on the device: callgrind instructions per pixel and time with its spread");

    out += "## Static cost\n\nFrom the optimized SPIR-V (`generator/spirv_cost.h`): scalar float operations, vector "
           "operations once per component, `OpDot` of N as 2N − 1, `Fma` as 1. The loop form is the supplement's "
           "listing as "
           "written (its loops and its numerics: `--forms loop --numerics paper`), compiled and optimized the same "
           "way.\n\n";
    out += table.markdown(names(kStaticColumns)) + "\n";
    out += "### The analytic lower bound\n\n" + std::string(kDerivation) + "\n\n";

    out +=
        fmt::format("## Measured cost\n\n{} rounds at {}x{}; every round dispatches each kernel once, in an order "
                    "rotated round to round. Times are {}: median, first and third quartile (Q1, Q3). Marginal = the "
                    "variant minus the gather-only kernel of its neighborhood (same loads and store, no clip). A "
                    "difference smaller than the larger interquartile range of the two is *within noise*: it is not "
                    "a saving or a loss this run can show.\n\n",
                    o.rounds, o.timing_size.first, o.timing_size.second,
                    result.device_clock ? "GPU timestamps around the dispatch" : "submit-to-fence wall times");
    if (o.callgrind)
        out +=
            fmt::format("callgrind: CPU instructions lavapipe executes per pixel for one {0}x{0} dispatch, counted by "
                        "callgrind around the dispatch alone (`LP_NUM_THREADS=0`, `bench/kdop-dispatch-probe`). It "
                        "repeats from run to run, so it is the number to compare where times are noisy.\n\n",
                        o.callgrind_size);
    out += table.markdown(names(kMeasuredColumns)) + "\n";
    const CostRow* gather = find_row(result, gather_key(Neighborhood::n9));
    const CostRow* copy = find_row(result, copy_key());
    if (gather && copy && std::isfinite(gather->ms.median))
        out += fmt::format("gather-n9 alone: {}; copy: {}.\n\n", run_ms(gather->ms.median, timing_pixels),
                           run_ms(copy->ms.median, timing_pixels));

    const Table hardened =
        table.rows_where([&](std::size_t r) { return std::isfinite(result.rows[r].paper_float_ops); });
    if (!hardened.rows().empty()) {
        out += "## Cost of hardening\n\nThe variants against the same variants with the paper's numerics "
               "(`--numerics paper`), which `kdop stress` shows returning NaN or colors outside the k-DOP on "
               "extreme input. Both were timed in the same interleaved rounds and counted by callgrind alike.\n\n";
        out += hardened.markdown(names(kHardeningColumns)) + "\n";
    }

    if (!result.sweep.sizes.empty()) {
        out += fmt::format("## Size sweep\n\nMedian of {} interleaved rounds per size.\n\n", o.sweep_rounds);
        out += sweep_table(result.sweep).markdown() + "\n";
        out += chart(2, "Time against pixel count");
    }
    return out;
}

Result<std::vector<OutputFile>> cost_charts(const BenchResult& result, const std::string& device,
                                            const std::filesystem::path& scratch,
                                            const std::filesystem::path& out_dir) {
    const auto names = cost_chart_names(result);
    const Table table = cost_table(result.rows);
    const Table clips = table.rows_where([&](std::size_t r) { return result.rows[r].key.is_clip(); });
    const std::string data = (scratch / "clips.dat").string();
    const std::vector<std::string> columns{
        "variant", "float_ops", "analytic_min_ops", "loop_float_ops", "instr_per_px", "loop_instr_per_px", "ms_median",
        "ms_q1",   "ms_q3",     "loop_ms_median",   "loop_ms_q1",     "loop_ms_q3",   "vs_loop_ms_noise"};
    if (auto ok = write_text(data, clips.gnuplot(columns)); !ok) return std::unexpected(ok.error());
    const CostRow* gather = find_row(result, gather_key(Neighborhood::n9));

    const std::string data_file = gnuplot_string(data);
    std::string script = gnuplot_terminal(1400, 560) + kChartStyle + gnuplot_output(scratch, 0);
    script += "set title 'Static cost: scalar float operations per pixel (optimized SPIR-V)'\nset ylabel 'float ops'\n";
    script += fmt::format("plot {0} using 2:xtic(1) title 'emitted (kdop)', '' using 3 title 'analytic lower bound', "
                          "'' using 4 title 'loop form (supplement)'\n",
                          data_file);
    // Measured cost: callgrind's instructions (when counted) above the times, drawn as medians with
    // their interquartile range; variants whose time is within noise of their loop form say so.
    const bool counted = measured_callgrind(result);
    script += gnuplot_terminal(1400, counted ? 1000 : 560) + gnuplot_output(scratch, 1) +
              fmt::format("set multiplot layout {},1\n", counted ? 2 : 1);
    if (counted) {
        script += "set title 'lavapipe: CPU instructions per pixel of one dispatch (callgrind, repeats exactly)'\n"
                  "set ylabel 'instructions / pixel'\n";
        script +=
            fmt::format("plot {0} using 5:xtic(1) title 'emitted (kdop)', '' using 6 title 'loop form'{1}\n", data_file,
                        gather ? fmt::format(", {} with lines dt 2 lw 2 lc rgb 'black' title 'gather-n9 alone'",
                                             gnuplot_number(gather->instr_per_px))
                               : "");
    }
    script += fmt::format(
        "set title {}\nset ylabel 'ms'\nset style histogram errorbars gap 1 lw 1\n",
        gnuplot_string(fmt::format(
            "{}: dispatch time, median with Q1..Q3; \"noise\": within the spread of its loop form", device)));
    script += fmt::format(
        "plot {0} using 7:8:9:xtic(1) title 'emitted (kdop), Q1..Q3', '' using 10:11:12 title 'loop form, Q1..Q3', "
        "'' using 0:(column(13) > 0 ? column(7) : 1/0):(\"noise\") with labels offset 0,1.5 notitle\n"
        "unset multiplot\n",
        data_file);

    if (!result.sweep.sizes.empty()) {
        const SweepResult& s = result.sweep;
        const std::string sweep_data = (scratch / "sweep.dat").string();
        if (auto ok = write_text(sweep_data, sweep_table(s).gnuplot({})); !ok) return std::unexpected(ok.error());
        script += gnuplot_terminal(1000, 700) + gnuplot_output(scratch, 2);
        script += "set style data linespoints\nset logscale xy\nset xtics rotate by 0 scale 1\nset yrange [*:*]\n"
                  "set xlabel 'Mpixel'\nset ylabel 'ms (median)'\nset title 'Dispatch time against pixel count'\n";
        script += "plot ";
        for (std::size_t k = 0; k < s.kernels.size(); ++k)
            script += fmt::format("{}{} using 2:{} title {}", k ? ", " : "", gnuplot_string(sweep_data), k + 3,
                                  gnuplot_string(s.kernels[k]));
        script += "\n";
    }
    return draw_charts(script, names, scratch, out_dir);
}

} // namespace kdop::bench
