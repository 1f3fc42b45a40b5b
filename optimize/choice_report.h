// What `kdop choose` writes: candidates.csv (and JSON), one row per candidate; choice.md, the
// table, the Pareto front of held-out ghosting against cost, the recommendation and why, with
// every setting it was measured with; its chart,
// choice.png (choice_chart.h); and
// kdop.manifest, exactly the recommended variant, which kdop_add_variants(MANIFEST) and
// `kdop gen --manifest` take.
#pragma once

#include "harness/output_set.h"
#include "harness/run_metadata.h"
#include "harness/table.h"
#include "optimize/choose.h"

#include <string>

namespace kdop {

Table candidates_table(const std::vector<Candidate>& candidates, const Metrics& metrics);

// `chart`: choice.png was drawn, and is shown.
std::string choice_markdown(const ChooseResult& result, const ChooseOptions& options, const RunMetadata& run,
                            bool chart = false);

// The recommended variant, with its `set:` line where its set is fitted or a --sets file's (a
// file beside the manifest, written by run_choose), and the resolve `options` measured it with
// (the manifest's gamma:, current-weight:, color-map:, history-filter: and dilate-motion: lines);
// empty where nothing is recommended.
std::string choice_manifest(const ChooseResult& result, const ChooseOptions& options);

// `kdop choose`'s run after its command line is read: choose(), then every file above (and the
// fitted sets' files, and the recommended --sets file's copy) added to `outputs` and written, all
// or nothing, by rank 0.
Result<ChooseResult> run_choose(const Context& context, const ChooseOptions& options, const Ranks& ranks,
                                OutputSet& outputs);

} // namespace kdop
