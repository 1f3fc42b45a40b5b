#include "bench/callgrind.h"

#include "core/parallel_for.h"
#include "harness/subprocess.h"

#include <fmt/format.h>

#include <cstdlib>
#include <fstream>
#include <mutex>

namespace kdop::bench {
namespace {

Result<double> measure_one(const CallgrindSetup& setup, const std::filesystem::path& valgrind,
                           const ProbeKernel& kernel) {
    const std::string& variant = kernel.name;
    const std::filesystem::path out = setup.scratch / (variant + ".callgrind");
    const std::filesystem::path log = setup.scratch / (variant + ".log");
    std::vector<std::string> argv{valgrind.string(),
                                  "--tool=callgrind",
                                  "--instr-atstart=no",
                                  "--callgrind-out-file=" + out.string(),
                                  setup.probe.string(),
                                  "--variant",
                                  kernel.variant,
                                  "--width",
                                  std::to_string(setup.size),
                                  "--height",
                                  std::to_string(setup.size)};
    if (!kernel.spirv.empty()) argv.insert(argv.end(), {"--spirv", kernel.spirv.string()});
    if (!setup.device.empty()) argv.insert(argv.end(), {"--device", setup.device});
    // Without Mesa's shader cache: on a miss its writer thread runs inside the counted dispatch and
    // adds tens of instructions per pixel, so the count would depend on what ran before.
    auto status = run_program(argv, log, {"LP_NUM_THREADS=0", "MESA_SHADER_CACHE_DISABLE=true"});
    if (!status) return std::unexpected(status.error());
    if (*status != 0)
        return fail(fmt::format("callgrind run of {} exited with {}:{}", variant, *status, log_tail(log, 8)));
    // The probe dumps once, at the end of the dispatch: <out>.1 holds exactly its instructions.
    std::ifstream dump(out.string() + ".1");
    for (std::string line; std::getline(dump, line);)
        if (line.rfind("totals:", 0) == 0)
            return std::strtod(line.c_str() + 7, nullptr) / (double(setup.size) * setup.size);
    return fail(fmt::format("callgrind run of {}: no 'totals:' line in {}.1", variant, out.string()));
}

} // namespace

Result<std::vector<double>> callgrind_instructions_per_pixel(const CallgrindSetup& setup,
                                                             const std::vector<ProbeKernel>& kernels, unsigned jobs,
                                                             Progress& progress) {
    const std::filesystem::path valgrind = find_program("valgrind");
    if (valgrind.empty()) return fail("valgrind not found in PATH (Debian: valgrind), or pass --no-callgrind");
    std::vector<Result<double>> results(kernels.size(), fail("not run"));
    std::mutex progress_mutex;
    parallel_for(kernels.size(), jobs, [&](std::size_t i) {
        results[i] = measure_one(setup, valgrind, kernels[i]);
        std::lock_guard lock(progress_mutex);
        progress.advance(kernels[i].name);
    });
    std::vector<double> per_pixel;
    for (auto& r : results) {
        if (!r) return std::unexpected(r.error());
        per_pixel.push_back(*r);
    }
    return per_pixel;
}

} // namespace kdop::bench
