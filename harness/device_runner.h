// The one place measurements run variants on the device: each image pair is uploaded once, each
// variant's pipeline is created once per runner and dispatched on the pair, and each output is read
// back and handed to the caller, variant by variant, in the order given. Stress, accuracy and any
// later measurement only say what to run and what to do with the outputs.
#pragma once

#include "core/result.h"
#include "images/image.h"
#include "runtime/context.h"
#include "runtime/kernel.h"
#include "runtime/rectify_pass.h"

#include <kdop/variant.h>

#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <tuple>

namespace kdop {

class DeviceRunner {
public:
    explicit DeviceRunner(const Context& context) : context_(context) {}

    // Called with the index of the variant in `variants` and its output; an error stops the run.
    using Each = std::function<Result<void>(std::size_t variant, const Image& output)>;

    // Both images must have one size; `gamma` goes to variance clips.
    Result<void> run(const Image& current, const Image& history, TextureFormat format,
                     std::span<const Variant* const> variants, float gamma, const Each& each);

    const Context& context() const { return context_; }

private:
    Result<Kernel*> kernel(const Variant& variant);
    Result<RectifyPass*> pass(std::uint32_t width, std::uint32_t height, TextureFormat format);

    const Context& context_;
    // By name and module hash: a variant rebuilt under the same name with other SPIR-V gets its own.
    std::map<std::pair<std::string, std::uint64_t>, std::unique_ptr<Kernel>> kernels_;
    std::map<std::tuple<std::uint32_t, std::uint32_t, TextureFormat>, std::unique_ptr<RectifyPass>> passes_;
};

} // namespace kdop
