#include "bench/set_cost.h"

#include "core/variant_key.h"
#include "core/write_files.h"
#include "generator/variant_builder.h"
#include "generator/variant_files.h"

namespace kdop::bench {

Result<double> marginal_clip_instructions(const AxisSet& set, Neighborhood neighborhood, const CallgrindSetup& setup,
                                          Progress& progress) {
    const VariantSpec spec{set, Mode::clip, neighborhood};
    auto built = build_variant(spec);
    if (!built) return std::unexpected(built.error());
    const std::filesystem::path module = setup.scratch / (built->name + ".spv");
    if (auto ok = write_files_atomically({{module, spirv_bytes(built->spirv)}}); !ok)
        return std::unexpected(ok.error());
    const VariantKey interface { "aabb", Mode::clip, neighborhood };
    const VariantKey gather = gather_key(neighborhood);
    auto counts = callgrind_instructions_per_pixel(
        setup, {{built->name, interface.name(), module}, {gather.name(), gather.name(), {}}}, 2, progress);
    if (!counts) return std::unexpected(counts.error());
    return (*counts)[0] - (*counts)[1];
}

} // namespace kdop::bench
