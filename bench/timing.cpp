#include "bench/timing.h"

#include "bench/bench_inputs.h"
#include "runtime/kernel.h"
#include "runtime/rectify_pass.h"

#include <fmt/format.h>

#include <cmath>
#include <memory>

namespace kdop::bench {

Result<TimingRun> time_interleaved(const Context& context, std::span<const Variant* const> kernels, std::uint32_t width,
                                   std::uint32_t height, unsigned rounds, Progress& progress) {
    auto pass = RectifyPass::create(context, width, height, TextureFormat::rgba32f);
    if (!pass) return std::unexpected(pass.error());
    auto [current, history] = bench_inputs(width, height);
    if (auto ok = (*pass)->upload(current, history); !ok) return std::unexpected(ok.error());

    std::vector<std::unique_ptr<Kernel>> loaded;
    for (const Variant* variant : kernels) {
        auto kernel = Kernel::create(context, *variant);
        if (!kernel) return std::unexpected(kernel.error());
        if (auto warm = (*pass)->dispatch(**kernel, 1.0f); !warm) return std::unexpected(warm.error());
        loaded.push_back(std::move(*kernel));
    }

    TimingRun run;
    run.ms.resize(kernels.size());
    for (unsigned round = 0; round < rounds; ++round) {
        for (std::size_t i = 0; i < loaded.size(); ++i) {
            const std::size_t k = (i + round) % loaded.size();
            auto timing = (*pass)->dispatch(*loaded[k], 1.0f);
            if (!timing) return std::unexpected(timing.error());
            // A queue either has timestamps for every dispatch or for none.
            run.device_clock = std::isfinite(timing->device_ms);
            run.ms[k].push_back(run.device_clock ? timing->device_ms : timing->wall_ms);
        }
        progress.advance(fmt::format("round {}/{} at {}x{}", round + 1, rounds, width, height));
    }
    return run;
}

} // namespace kdop::bench
