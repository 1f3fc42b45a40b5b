// Where a measurement was taken: what the report's header says besides the device.
#pragma once

#include <string>

namespace kdop::bench {

std::string utc_now_iso8601();
// CPU model and core count, from /proc/cpuinfo.
std::string machine_description();
// The source tree's git commit (with "-dirty" for uncommitted changes), or "unknown" where the
// tree or git is not there (an installed kdop).
std::string source_commit();

} // namespace kdop::bench
