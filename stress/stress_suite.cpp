#include "stress_suite.h"

#include "kernel.h"
#include "rectify_pass.h"
#include "runnable_variant.h"
#include "stress_cases.h"

#include <fmt/format.h>

#include <map>

namespace kdop {

std::size_t StressRun::failing_cells() const {
    std::size_t n = 0;
    for (const auto& row : results)
        for (const CheckResult& cell : row) n += cell.violations() > 0;
    return n;
}

Result<StressRun> run_stress(const Context& context, const StressOptions& options, const StressProgress& progress) {
    for (const VariantSpec& spec : options.specs)
        if (spec.mode != Mode::clip && spec.mode != Mode::varclip)
            return fail(fmt::format("{}: only clip variants can be stressed", variant_name(spec)));
    auto built = build_variants(options.specs);
    if (!built) return std::unexpected(built.error());

    StressRun run;
    std::map<std::string, std::vector<StressCase>> cases_by_set;
    run.device_name = context.device_name();
    run.driver_info = context.driver_info();
    for (BuiltVariant& b : *built) {
        const RunnableVariant variant(std::move(b));
        const VariantSpec& spec = variant.built().spec;
        auto kernel = Kernel::create(context, variant.variant());
        if (!kernel) return std::unexpected(kernel.error());
        const ClipUnderTest clip(spec, options.gamma);
        // Cases depend on the axis set (the parallel rays), so variants of one set share them.
        auto [found, added] = cases_by_set.try_emplace(spec.set.name);
        if (added) found->second = make_stress_cases(spec.set, options.seed);
        const std::vector<StressCase>& cases = found->second;
        if (run.cases.empty())
            for (const StressCase& c : cases) {
                run.cases.push_back(c.name);
                run.case_descriptions.push_back(c.description);
            }
        std::vector<CheckResult>& row = run.results.emplace_back();
        for (const StressCase& c : cases) {
            auto pass = RectifyPass::create(context, c.current.width, c.current.height, c.format);
            if (!pass) return std::unexpected(pass.error());
            if (auto ok = (*pass)->upload(c.current, c.history); !ok) return std::unexpected(ok.error());
            if (auto ok = (*pass)->dispatch(**kernel, options.gamma); !ok) return std::unexpected(ok.error());
            auto output = (*pass)->download();
            if (!output) return std::unexpected(output.error());
            row.push_back(check_invariants(clip, c.current, c.history, *output));
        }
        run.variants.push_back(variant.built().name);
        if (progress) progress(run.variants.size(), options.specs.size(), run.variants.back());
    }
    return run;
}

} // namespace kdop
