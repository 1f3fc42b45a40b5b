// GPU test helpers: one validated Vulkan context for the whole test binary, the harness's device
// runner on it (pipelines created once per variant and module), and the comparison of images
// against the CPU reference.
#pragma once

#include "generator/variant_spec.h"
#include "harness/device_runner.h"
#include "harness/variant_catalog.h"
#include "images/image.h"
#include "runtime/context.h"
#include "runtime/kernel.h"
#include "runtime/rectify_pass.h"

#include <kdop/variant.h>

#include <gtest/gtest.h>

#include <string>

namespace kdop::test {

// The context of the tests: lavapipe (or $KDOP_DEVICE) with the Khronos validation layer on.
// A failure to create it fails the calling test.
Context& gpu();

// The built-in registry entry called `name` (fails the test when missing).
const Variant& builtin_variant(const std::string& name);

// One device runner on gpu() and one variant catalog (the built-in sets) for the test binary.
DeviceRunner& runner();
VariantCatalog& catalog();

// Runs `variant` once on the pair (through runner(), so its pipeline is created once).
Image run_on_gpu(const Variant& variant, const Image& current, const Image& history,
                 TextureFormat format = TextureFormat::rgba32f, float gamma = 1.0f);

// The spec (axis set, mode, neighborhood) of a built-in clip variant, for the CPU reference.
VariantSpec builtin_spec(const Variant& variant);

// Largest per-pixel error |a - b| (max over RGB), divided by the pixel's color magnitude
// max(1, |current|, |history|) (max norms): float32 rounding grows with the values, so a fixed
// absolute bound would be too loose for LDR and too tight for HDR.
struct ErrorReport {
    double max_relative = 0;
    std::uint32_t x = 0, y = 0;
};
ErrorReport relative_error(const Image& a, const Image& b, const Image& current, const Image& history);

// A fixture for GPU tests: each checks at its end that the validation layer reported nothing during it.
class ValidationChecked : public ::testing::Test {
protected:
    void SetUp() override { seen_ = gpu().validation_messages().size(); }
    void TearDown() override {
        auto messages = gpu().validation_messages();
        for (std::size_t i = seen_; i < messages.size(); ++i) ADD_FAILURE() << "validation: " << messages[i];
    }

private:
    std::size_t seen_ = 0;
};

} // namespace kdop::test
