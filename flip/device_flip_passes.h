// The compute passes of device FLIP (flip/device_flip.h), built from shader_templates/flip.comp.in
// with the kernels and constants the CPU code computes, each as the float it computes with.
#pragma once

#include "core/result.h"
#include "flip/flip.h"
#include "runtime/context.h"

#include <cstdint>
#include <memory>

namespace kdop {

class RunnableVariant;

// The template's FLIP_PASS values.
enum FlipPass : int { kFlipHorizontal, kFlipVertical, kFlipRowSums, kFlipLoad, kFlipLuminance, kFlipPasses };

// Pixels each invocation of pass `pass` computes along its filter's direction (the template's
// FLIP_RUN): runs on a CPU device, one pixel on a GPU.
std::uint32_t flip_run_length(const Context& context, int pass);

// Pass `pass` compiled (unoptimized) for `cpu`'s pixels per degree and runs of `run` pixels.
Result<std::unique_ptr<RunnableVariant>> build_flip_pass(const LdrFlip& cpu, int pass, std::uint32_t run);

} // namespace kdop
