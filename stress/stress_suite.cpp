#include "stress/stress_suite.h"

#include "stress/stress_cases.h"

#include <fmt/format.h>

#include <algorithm>

namespace kdop {
namespace {

// The selected sets in order of first appearance: cases are built per set (the parallel rays
// follow its slabs), and all variants of a set run on them together.
std::vector<std::string> sets_of(const std::vector<VariantKey>& keys) {
    std::vector<std::string> sets;
    for (const VariantKey& k : keys)
        if (std::ranges::find(sets, k.set) == sets.end()) sets.push_back(k.set);
    return sets;
}

} // namespace

std::size_t StressRun::failing_cells() const {
    std::size_t n = 0;
    for (const auto& row : results)
        for (const CheckResult& cell : row) n += cell.violations() > 0;
    return n;
}

std::size_t stress_steps(const StressOptions& options) {
    return sets_of(options.variants).size() * stress_case_count();
}

Result<StressRun> run_stress(DeviceRunner& runner, VariantCatalog& catalog, const StressOptions& options,
                             Progress* progress) {
    for (const VariantKey& key : options.variants)
        if (!key.is_clip()) return fail(fmt::format("{}: only clip variants can be stressed", key.name()));
    auto variants = catalog.find_all(options.variants, "--sets");
    if (!variants) return std::unexpected(variants.error());

    StressRun run;
    for (const VariantKey& key : options.variants) run.variants.push_back(key.name());
    run.results.resize(options.variants.size());
    for (const std::string& set_name : sets_of(options.variants)) {
        auto set = catalog.set(set_name, "--sets");
        if (!set) return std::unexpected(set.error());
        std::vector<std::size_t> members; // indices into options.variants
        std::vector<const Variant*> kernels;
        std::vector<ClipUnderTest> clips;
        for (std::size_t v = 0; v < options.variants.size(); ++v) {
            const VariantKey& key = options.variants[v];
            if (key.set != set_name) continue;
            members.push_back(v);
            kernels.push_back((*variants)[v]);
            auto spec = catalog.spec(key, "--sets");
            if (!spec) return std::unexpected(spec.error());
            clips.emplace_back(*spec, options.gamma);
        }
        const std::vector<StressCase> cases = make_stress_cases(*set, options.seed);
        if (run.cases.empty())
            for (const StressCase& c : cases) {
                run.cases.push_back(c.name);
                run.case_descriptions.push_back(c.description);
            }
        for (const StressCase& c : cases) {
            auto ran = runner.run(c.current, c.history, c.format, kernels, options.gamma,
                                  [&](std::size_t i, const Image& output) -> Result<void> {
                                      run.results[members[i]].push_back(
                                          check_invariants(clips[i], c.current, c.history, output));
                                      return {};
                                  });
            if (!ran) return fail(fmt::format("stress case {}: {}", c.name, ran.error().message));
            if (progress) progress->advance(fmt::format("{} on {}", set_name, c.name));
        }
    }
    return run;
}

} // namespace kdop
