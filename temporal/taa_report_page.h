// report.html: what `kdop taa` measured, on one page a browser opens from the output folder with
// no network: the table (sortable), the trade and over-time charts, the ghosting pictures, and a
// frame viewer over the frames viewer_frames.h kept (two variants side by side or flipped with a
// key, the FLIP map over or instead of the frame, each variant's worst frame a click away). Style
// and script are kdop's own (temporal/report_page/), inline; the images are the PNGs beside it.
#pragma once

#include "harness/run_metadata.h"
#include "temporal/taa_report.h"
#include "temporal/viewer_frames.h"

#include <string>
#include <vector>

namespace kdop {

// The page for `rows` (taa.csv's), with `settings`' charts and pictures, `viewer`'s frames of
// `variants` (the viewer's variant order) and `run`'s metadata.
std::string taa_report_html(const std::vector<TaaRow>& rows, const RunMetadata& run, const TaaReportSettings& settings,
                            const std::vector<std::string>& variants, const std::vector<ViewerSequence>& viewer);

} // namespace kdop
