#include "harness/device_runner.h"

#include <fmt/format.h>

namespace kdop {

Result<Kernel*> DeviceRunner::kernel(const Variant& variant) {
    auto& slot = kernels_[{variant.name, variant.spirv_hash}];
    if (!slot) {
        auto created = Kernel::create(context_, variant);
        if (!created) return std::unexpected(created.error());
        slot = std::move(*created);
    }
    return slot.get();
}

Result<RectifyPass*> DeviceRunner::pass(std::uint32_t width, std::uint32_t height, TextureFormat format) {
    auto& slot = passes_[{width, height, format}];
    if (!slot) {
        auto created = RectifyPass::create(context_, width, height, format);
        if (!created) return std::unexpected(created.error());
        slot = std::move(*created);
    }
    return slot.get();
}

Result<void> DeviceRunner::run(const Image& current, const Image& history, TextureFormat format,
                               std::span<const Variant* const> variants, float gamma, const Each& each) {
    if (current.width != history.width || current.height != history.height)
        return fail(fmt::format("current frame is {}x{} but history is {}x{}", current.width, current.height,
                                history.width, history.height));
    auto target = pass(current.width, current.height, format);
    if (!target) return std::unexpected(target.error());
    if (auto ok = (*target)->upload(current, history); !ok) return ok;
    for (std::size_t v = 0; v < variants.size(); ++v) {
        auto k = kernel(*variants[v]);
        if (!k) return std::unexpected(k.error());
        if (auto ok = (*target)->dispatch(**k, gamma); !ok) return std::unexpected(ok.error());
        auto output = (*target)->download();
        if (!output) return std::unexpected(output.error());
        if (auto ok = each(v, *output); !ok) return ok;
    }
    return {};
}

} // namespace kdop
