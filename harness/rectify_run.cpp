#include "harness/rectify_run.h"

#include "core/input_files.h"
#include "core/memory_budget.h"
#include "core/write_files.h"
#include "runtime/kernel.h"

#include <fmt/format.h>

#include <filesystem>

namespace kdop {

Result<RectifyRunResult> run_rectify(const Variant& variant, const RectifyRunOptions& o) {
    if (o.gamma && variant.mode != Mode::varclip)
        return usage_fail(fmt::format("--gamma: {} is not a variance clip and takes no gamma", variant.name));
    if (auto ok = check_image_writable(o.out); !ok)
        return std::unexpected(Error{"--out: " + ok.error().message, ok.error().usage});
    const std::filesystem::path inputs[] = {o.current, o.history};
    if (auto ok = check_output_file(o.out, "--out"); !ok) return usage_fail(ok.error().message);
    if (auto ok = check_not_an_input(o.out, "--out", inputs); !ok) return std::unexpected(ok.error());

    // The device first: its size limit is checked on each image's header, before its pixels.
    auto context = Context::create(o.device);
    if (!context) return fail(context.error().message);
    const std::uint32_t max_side = (*context)->properties().limits.maxImageDimension2D;
    auto current = read_image(o.current, max_side, o.input_space);
    if (!current) return fail(current.error().message);
    auto history = read_image(o.history, max_side, o.input_space);
    if (!history) return fail(history.error().message);
    if (current->width != history->width || current->height != history->height)
        return fail(fmt::format("--history: {} is {}x{} but --current {} is {}x{}", o.history, history->width,
                                history->height, o.current, current->width, current->height));
    if (auto ok =
            check_memory(fmt::format("--current {}: a {}x{} rectification", o.current, current->width, current->height),
                         rectify_pass_bytes(current->width, current->height));
        !ok)
        return fail(ok.error().message);
    auto kernel = Kernel::create(**context, variant);
    if (!kernel) return fail(kernel.error().message);
    auto pass = RectifyPass::create(**context, current->width, current->height, o.format);
    if (!pass) return fail(pass.error().message);
    if (auto ok = (*pass)->upload(*current, *history); !ok) return fail(ok.error().message);

    RectifyRunResult result{
        (*context)->device_name(), current->width, current->height, (*kernel)->creation_ms(), {}, {}};
    for (unsigned i = 0; i < o.repeat; ++i) {
        auto timing = (*pass)->dispatch(**kernel, static_cast<float>(o.gamma.value_or(1.0)));
        if (!timing) return fail(timing.error().message);
        result.wall_ms.push_back(timing->wall_ms);
        result.device_ms.push_back(timing->device_ms);
    }
    auto rectified = (*pass)->download();
    if (!rectified) return fail(rectified.error().message);
    if (auto ok = write_image(o.out, *rectified); !ok) return fail(ok.error().message);
    return result;
}

} // namespace kdop
