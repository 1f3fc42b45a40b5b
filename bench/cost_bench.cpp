#include "bench/cost_bench.h"

#include "bench/callgrind.h"
#include "bench/timing.h"
#include "core/builtin_sets.h"
#include "core/write_files.h"
#include "generator/analytic_cost.h"
#include "generator/spirv_module.h"
#include "generator/variant_files.h"
#include "harness/progress.h"
#include "harness/statistics.h"

#include <fmt/format.h>

#include <algorithm>

namespace kdop::bench {
namespace {

std::span<const std::uint32_t> words(const Variant& v) { return {v.spirv, v.spirv_word_count}; }

const std::vector<VariantKey> kBaselines{gather_key(Neighborhood::n9), gather_key(Neighborhood::n5), copy_key()};

CostRow static_row(const VariantKey& key, const Variant& v) {
    CostRow row;
    row.key = key;
    row.k = 2 * v.axis_count;
    row.spirv_instructions = count_spirv(words(v)).instructions;
    row.float_ops = count_float_ops(words(v));
    return row;
}

Timing timing_of(const std::vector<double>& samples) {
    return {median(samples), quantile(samples, 0.25), quantile(samples, 0.75)};
}

// The kernels every row needs: itself, the supplement's listing of it and its paper twin where it
// has them.
struct Kernels {
    std::vector<VariantKey> keys;
    std::vector<const Variant*> variants;
    std::size_t index(const VariantKey& key) const {
        return static_cast<std::size_t>(std::ranges::find(keys, key) - keys.begin());
    }
    bool has(const VariantKey& key) const { return index(key) < keys.size(); }
};

// The supplement's listing as written: the loop form with the paper's numerics, whatever the
// variant's own, so every variant is held against the same baseline.
std::optional<VariantKey> loop_of(const VariantKey& key) {
    if (!key.is_clip()) return std::nullopt;
    return key.with(Form::loop).with(Numerics::paper);
}
std::optional<VariantKey> paper_of(const VariantKey& key) {
    if (!key.is_clip() || key.numerics == Numerics::paper) return std::nullopt;
    return key.with(Numerics::paper);
}

// A kernel for the callgrind probe, which runs in its own process: an embedded variant by name;
// any other by its module, written to the scratch directory, with the interface of the embedded
// variant of the same mode and neighborhood (every clip of one mode and neighborhood has the same
// bindings and push constants, and the probe binds them by name).
Result<ProbeKernel> probe_kernel(const VariantKey& key, const Variant& v, VariantCatalog& catalog,
                                 const std::filesystem::path& scratch) {
    if (VariantCatalog::is_embedded(v)) return ProbeKernel{key.name(), key.name(), {}};
    const VariantKey donor_key = key.with_set(kRgbBox).with(Form::unrolled).with(Numerics::hardened);
    auto donor = catalog.find(donor_key);
    if (!donor) return std::unexpected(donor.error());
    if ((*donor)->binding_count != v.binding_count || (*donor)->push_constant_size != v.push_constant_size)
        return fail(fmt::format("{}: its interface differs from {}'s; the callgrind probe cannot run it", key.name(),
                                donor_key.name()));
    const std::filesystem::path module = scratch / (key.name() + ".spv");
    if (auto ok = write_files_atomically({{module, spirv_bytes(words(v))}}); !ok) return std::unexpected(ok.error());
    return ProbeKernel{key.name(), donor_key.name(), module};
}

} // namespace

std::vector<VariantKey> sweep_kernels(const std::vector<VariantKey>& variants, const VariantCatalog& catalog) {
    std::vector<VariantKey> kernels{gather_key(Neighborhood::n9), copy_key()};
    std::optional<VariantKey> largest;
    std::size_t largest_axes = 0;
    for (const VariantKey& key : variants) {
        if (key.mode != Mode::clip || key.neighborhood != Neighborhood::n9) continue;
        kernels.push_back(key);
        auto set = catalog.set(key.set, "--variants");
        if (set && set->axes.size() > largest_axes) {
            largest = key;
            largest_axes = set->axes.size();
        }
    }
    if (largest) kernels.push_back(largest->with(Form::loop));
    return kernels;
}

Result<BenchResult> run_cost_bench(const Context& context, VariantCatalog& catalog, const BenchOptions& options) {
    BenchResult result;
    Kernels all;
    for (const VariantKey& key : options.variants) all.keys.push_back(key);
    for (const VariantKey& key : kBaselines) all.keys.push_back(key);
    for (const VariantKey& key : options.variants)
        for (const auto& companion : {loop_of(key), paper_of(key)})
            // A companion may be selected itself (dop32-clip-n9 and dop32-clip-n9-paper): once.
            if (companion && !all.has(*companion)) all.keys.push_back(*companion);
    auto found = catalog.find_all(all.keys, "--variants");
    if (!found) return std::unexpected(found.error());
    all.variants = std::move(*found);

    // Static cost, and the analytic lower bound from the set's axes.
    for (std::size_t i = 0; i < options.variants.size() + kBaselines.size(); ++i) {
        const VariantKey& key = all.keys[i];
        CostRow row = static_row(key, *all.variants[i]);
        if (key.is_clip()) {
            auto set = catalog.set(key.set, "--variants");
            if (!set) return std::unexpected(set.error());
            row.analytic_min_ops = double(analytic_min_float_ops(*set, key.mode, key.neighborhood));
            row.loop_float_ops = double(count_float_ops(words(*all.variants[all.index(*loop_of(key))])).total());
            if (auto paper = paper_of(key))
                row.paper_float_ops = double(count_float_ops(words(*all.variants[all.index(*paper)])).total());
        }
        result.rows.push_back(row);
    }

    // Every kernel at the timing size, interleaved.
    {
        Progress progress(fmt::format("timing {} kernels,", all.variants.size()), options.rounds);
        auto run = time_interleaved(context, all.variants, options.timing_size.first, options.timing_size.second,
                                    options.rounds, progress);
        if (!run) return std::unexpected(run.error());
        result.device_clock = run->device_clock;
        const auto timing = [&](const VariantKey& key) { return timing_of(run->ms[all.index(key)]); };
        for (CostRow& row : result.rows) {
            row.ms = timing(row.key);
            if (!row.key.is_clip()) continue;
            row.loop_ms = timing(*loop_of(row.key));
            row.gather_ms = timing(gather_key(row.key.neighborhood));
            if (auto paper = paper_of(row.key)) row.paper_ms = timing(*paper);
        }
        for (CostRow& row : result.rows) {
            const VariantKey aabb = row.key.with_set(kRgbBox);
            if (row.key.is_clip() && all.has(aabb)) row.ms_vs_aabb = row.ms.median / timing(aabb).median;
        }
    }

    if (!options.sweep_sizes.empty()) {
        SweepResult& sweep = result.sweep;
        const std::vector<VariantKey> keys = sweep_kernels(options.variants, catalog);
        auto swept = catalog.find_all(keys, "--variants");
        if (!swept) return std::unexpected(swept.error());
        for (const VariantKey& key : keys) sweep.kernels.push_back(key.name());
        sweep.sizes = options.sweep_sizes;
        Progress progress(fmt::format("size sweep of {} kernels,", swept->size()),
                          sweep.sizes.size() * options.sweep_rounds);
        for (const Size& size : sweep.sizes) {
            auto run = time_interleaved(context, *swept, size.first, size.second, options.sweep_rounds, progress);
            if (!run) return std::unexpected(run.error());
            std::vector<double> medians;
            for (const auto& ms : run->ms) medians.push_back(median(ms));
            sweep.ms_median.push_back(medians);
        }
    }

    if (options.callgrind) {
        std::vector<ProbeKernel> probes;
        for (std::size_t i = 0; i < all.keys.size(); ++i) {
            auto probe = probe_kernel(all.keys[i], *all.variants[i], catalog, options.scratch);
            if (!probe) return std::unexpected(probe.error());
            probes.push_back(std::move(*probe));
        }
        CallgrindSetup setup{options.probe, options.scratch, options.callgrind_size, options.device};
        Progress progress("callgrind", probes.size());
        auto counts = callgrind_instructions_per_pixel(setup, probes, options.jobs, progress);
        if (!counts) return std::unexpected(counts.error());
        const auto count = [&](const VariantKey& key) { return (*counts)[all.index(key)]; };
        for (CostRow& row : result.rows) {
            row.instr_per_px = count(row.key);
            if (!row.key.is_clip()) continue;
            row.loop_instr_per_px = count(*loop_of(row.key));
            if (auto paper = paper_of(row.key)) row.paper_instr_per_px = count(*paper);
        }
    }
    return result;
}

} // namespace kdop::bench
