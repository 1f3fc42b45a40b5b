// `kdop run`'s work after its command line is read: one variant rectifies a history against a
// current frame on the device, optionally dispatched several times to time it, and the rectified
// history is written as an image.
#pragma once

#include "core/result.h"
#include "images/image_io.h"
#include "runtime/context.h"
#include "runtime/rectify_pass.h"

#include <kdop/variant.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace kdop {

struct RectifyRunOptions {
    std::string current, history, out; // images; `out` in a format OpenImageIO writes
    InputSpace input_space = InputSpace::from_file;
    TextureFormat format = TextureFormat::rgba32f; // the inputs' upload format
    std::optional<double> gamma;                   // variance clips only [default: 1]
    unsigned repeat = 1;                           // dispatches
    ContextOptions device;
};

struct RectifyRunResult {
    std::string device;
    std::uint32_t width = 0, height = 0;
    double creation_ms = 0;                 // the pipeline's
    std::vector<double> wall_ms, device_ms; // per dispatch
};

// Checks every option and file before the work (Error::usage where the command line is at fault),
// then rectifies with `variant` and writes options.out.
Result<RectifyRunResult> run_rectify(const Variant& variant, const RectifyRunOptions& options);

} // namespace kdop
