#include "stress/stress_study.h"

#include "harness/device_runner.h"
#include "harness/output_set.h"
#include "harness/progress.h"
#include "stress/stress_report.h"

#include <fmt/format.h>

#include <optional>
#include <utility>

namespace kdop {

Result<StressStudy> stress_study(const std::vector<VariantSpec>& specs, VariantCatalog& catalog,
                                 const StressStudyOptions& options) {
    std::optional<OutputSet> outputs;
    if (!options.out.empty()) {
        auto prepared = OutputSet::prepare(options.out);
        if (!prepared) return fail(prepared.error().message);
        outputs = std::move(*prepared);
    }
    auto context = Context::create(options.device);
    if (!context) return fail(context.error().message);

    const StressOptions stress{keys_of(specs), options.seed, options.gamma};
    DeviceRunner runner(**context);
    Progress progress(fmt::format("stress on {},", (*context)->device_name()), stress_steps(stress));
    auto run = run_stress(runner, catalog, stress, &progress);
    progress.finish();
    if (!run) return fail(run.error().message);

    StressStudy study{std::move(*run), describe_run(**context), (*context)->validation_messages()};
    study.run_info.seed = options.seed;
    if (outputs) {
        outputs->add_table("stress", stress_table(study.run), study.run_info);
        outputs->add("report.md", stress_report_markdown(study.run, study.run_info, options.gamma));
        if (auto ok = outputs->write(); !ok) return fail(ok.error().message);
    }
    return study;
}

} // namespace kdop
