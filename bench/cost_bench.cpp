#include "cost_bench.h"

#include "analytic_cost.h"
#include "callgrind.h"
#include "context.h"
#include "variant_files.h"
#include "progress.h"
#include "runnable_variant.h"
#include "spirv_module.h"
#include "statistics.h"
#include "timing.h"
#include "variant_builder.h"
#include "variant_spec.h"

#include <kdop_builtin_variants.h>

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <memory>

namespace kdop::bench {
namespace {

const Variant& registered(const std::string& name) {
    const Variant* v = builtin::variants().find(name.c_str());
    if (!v) throw std::logic_error("kdop bench: no built-in variant " + name); // names are checked by the caller
    return *v;
}

std::span<const std::uint32_t> words(const Variant& v) { return {v.spirv, v.spirv_word_count}; }

std::string gather_of(const Variant& v) { return fmt::format("gather-{}", to_string(v.neighborhood)); }

CostRow static_row(const Variant& v) {
    CostRow row;
    row.variant = v.name;
    row.axis_set = v.axis_set;
    row.mode = to_string(v.mode);
    row.neighborhood = v.mode == Mode::copy ? "" : to_string(v.neighborhood);
    row.k = 2 * v.axis_count;
    row.spirv_instructions = count_spirv(words(v)).instructions;
    row.float_ops = count_float_ops(words(v));
    return row;
}

} // namespace

std::vector<std::string> sweep_kernels(const std::vector<std::string>& variants) {
    std::vector<std::string> kernels{"gather-n9", "copy"};
    for (const std::string& name : variants)
        if (name.ends_with("-clip-n9")) kernels.push_back(name);
    if (std::ranges::find(variants, "dop32-clip-n9") != variants.end()) kernels.push_back("dop32-clip-n9-loop");
    return kernels;
}

Result<BenchResult> run_cost_bench(const BenchOptions& options) {
    BenchResult result;
    const std::vector<std::string> baselines{"gather-n9", "gather-n5", "copy"};

    // Static cost, and the analytic minimum from the set's axes.
    std::map<std::string, AxisSet> sets;
    for (const std::string& name : options.variants) {
        const Variant& v = registered(name);
        if (!sets.contains(v.axis_set)) {
            auto set = resolve_axis_set(v.axis_set);
            if (!set) return std::unexpected(set.error());
            sets.emplace(v.axis_set, *set);
        }
        CostRow row = static_row(v);
        row.baseline_float_ops = double(count_float_ops(words(registered(name + "-loop"))).total());
        row.analytic_min_ops = double(analytic_min_float_ops(sets.at(v.axis_set), v.mode, v.neighborhood));
        result.rows.push_back(row);
    }
    for (const std::string& name : baselines) result.rows.push_back(static_row(registered(name)));

    // The same variants with the paper's numerics, built here: what the hardening costs.
    std::vector<VariantSpec> paper_specs;
    for (const std::string& name : options.variants) {
        const Variant& v = registered(name);
        VariantSpec spec{sets.at(v.axis_set), v.mode, v.neighborhood};
        spec.numerics = Numerics::paper;
        paper_specs.push_back(spec);
    }
    auto paper_built = build_variants(paper_specs);
    if (!paper_built) return std::unexpected(paper_built.error());
    std::vector<std::unique_ptr<RunnableVariant>> paper;
    for (std::size_t i = 0; i < paper_built->size(); ++i) {
        paper.push_back(std::make_unique<RunnableVariant>(std::move((*paper_built)[i])));
        result.rows[i].paper_float_ops = double(count_float_ops(paper.back()->built().spirv).total());
    }

    // Every kernel at the timing size, interleaved: variants, their loop forms, the baselines.
    std::vector<const Variant*> kernels;
    for (const std::string& name : options.variants) kernels.push_back(&registered(name));
    for (const std::string& name : options.variants) kernels.push_back(&registered(name + "-loop"));
    for (const std::string& name : baselines) kernels.push_back(&registered(name));
    for (const auto& p : paper) kernels.push_back(&p->variant());

    auto context = Context::create({options.device, false});
    if (!context) return std::unexpected(context.error());
    result.device_name = (*context)->device_name();
    result.driver_info = (*context)->driver_info();
    {
        Progress progress(fmt::format("timing {} kernels,", kernels.size()), options.rounds);
        auto run = time_interleaved(**context, kernels, options.timing_size.first, options.timing_size.second,
                                    options.rounds, progress);
        if (!run) return std::unexpected(run.error());
        result.device_clock = run->device_clock;
        std::map<std::string, std::vector<double>> samples;
        for (std::size_t k = 0; k < kernels.size(); ++k) samples[kernels[k]->name] = run->ms[k];
        for (CostRow& row : result.rows) {
            row.ms_median = median(samples.at(row.variant));
            row.ms_spread = interquartile_range(samples.at(row.variant));
            if (samples.contains(row.variant + "-loop")) row.baseline_ms_median = median(samples.at(row.variant + "-loop"));
            if (samples.contains(row.variant + "-paper")) row.paper_ms_median = median(samples.at(row.variant + "-paper"));
            if (!row.axis_set.empty())
                row.marginal_ms = row.ms_median - median(samples.at(gather_of(registered(row.variant))));
        }
        for (CostRow& row : result.rows) {
            auto aabb = std::ranges::find_if(result.rows, [&](const CostRow& r) {
                return r.axis_set == "aabb" && r.mode == row.mode && r.neighborhood == row.neighborhood;
            });
            if (!row.axis_set.empty() && aabb != result.rows.end()) row.ms_vs_aabb = row.ms_median / aabb->ms_median;
        }
    }

    if (!options.sweep_sizes.empty()) {
        SweepResult& sweep = result.sweep;
        sweep.kernels = sweep_kernels(options.variants);
        sweep.sizes = options.sweep_sizes;
        std::vector<const Variant*> swept;
        for (const std::string& name : sweep.kernels) swept.push_back(&registered(name));
        Progress progress(fmt::format("size sweep of {} kernels,", swept.size()), sweep.sizes.size() * options.sweep_rounds);
        for (const Size& size : sweep.sizes) {
            auto run = time_interleaved(**context, swept, size.first, size.second, options.sweep_rounds, progress);
            if (!run) return std::unexpected(run.error());
            std::vector<double> medians;
            for (const auto& ms : run->ms) medians.push_back(median(ms));
            sweep.ms_median.push_back(medians);
        }
    }

    if (options.callgrind) {
        std::vector<ProbeKernel> probes;
        for (const CostRow& row : result.rows) probes.push_back({row.variant, row.variant, {}});
        for (const std::string& name : options.variants) probes.push_back({name + "-loop", name + "-loop", {}});
        // The probe runs each paper module with its default's interface (built in options.variants' order).
        std::vector<OutputFile> paper_modules;
        for (std::size_t i = 0; i < paper.size(); ++i) {
            paper_modules.push_back(spirv_file(paper[i]->built(), options.scratch));
            probes.push_back({paper[i]->built().name, options.variants[i], paper_modules.back().path});
        }
        if (auto ok = write_files_atomically(paper_modules); !ok) return std::unexpected(ok.error());
        CallgrindSetup setup{options.probe, options.scratch, options.callgrind_size, options.device};
        Progress progress("callgrind", probes.size());
        auto counts = callgrind_instructions_per_pixel(setup, probes, options.jobs, progress);
        if (!counts) return std::unexpected(counts.error());
        std::map<std::string, double> per_pixel;
        for (std::size_t i = 0; i < probes.size(); ++i) per_pixel[probes[i].name] = (*counts)[i];
        for (CostRow& row : result.rows) {
            row.instr_per_px = per_pixel.at(row.variant);
            if (per_pixel.contains(row.variant + "-loop")) row.baseline_instr_per_px = per_pixel.at(row.variant + "-loop");
            if (per_pixel.contains(row.variant + "-paper")) row.paper_instr_per_px = per_pixel.at(row.variant + "-paper");
        }
    }
    return result;
}

} // namespace kdop::bench
