// The two resolves of this example (resolve_compute.comp; fullscreen.vert + resolve_fragment.frag),
// or their HLSL ports (hlsl_resolve_compute.cs.hlsl; hlsl_fullscreen.vs.hlsl +
// hlsl_resolve_fragment.ps.hlsl: a separate sampler where GLSL combines one), run on a caller's
// Vulkan device as an engine's frame runs them: pipelines, descriptor pool and set writes through
// kdop/vulkan_pipeline.h from the registry entries alone, images and buffers sized and typed from their reflection (the
// storage image's format, the uniform blocks' sizes), then one submission that resolves the same frames both ways.
//
// Upscaler runs the TAAU resolve (upscale_compute.comp, or hlsl_upscale_compute.cs.hlsl) through
// kdop's run helper (kdop/resolve_runner.h): input-size color and motion, output-size history and
// output, the history kept on the device, the jitter in push constants.
//
// Compiled with VK_NO_PROTOTYPES: every Vulkan call goes through vkGetInstanceProcAddr and
// vkGetDeviceProcAddr, as with volk, so nothing here links the loader.
#pragma once

#include <kdop/resolve_runner.h>
#include <kdop/variant.h>

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace engine {

// The caller's device, as kdop's run helper takes it; its queue must do graphics and compute.
using Device = kdop::RunnerDevice;

// The registry entries of the three shaders, GLSL or HLSL.
struct Shaders {
    const kdop::Variant* compute = nullptr;  // resolve_compute, hlsl_resolve_compute
    const kdop::Variant* vertex = nullptr;   // fullscreen, hlsl_fullscreen
    const kdop::Variant* fragment = nullptr; // resolve_fragment, hlsl_resolve_fragment
};

// One frame's inputs; colors are RGBA floats, row-major from the top-left pixel.
struct Frames {
    std::vector<float> current;    // this frame
    std::vector<float> history;    // last frame's resolve
    std::array<float, 2> motion{}; // screen motion in pixels
    float current_weight = 0.1f;
};

struct Resolved {
    std::vector<float> compute;       // RGBA, the compute resolve's storage image
    std::vector<float> fragment;      // RGBA, the fragment resolve's color attachment
    std::vector<float> clip_distance; // per pixel, the compute resolve's storage buffer
};

class Resolver {
public:
    // Pipelines and resources for width x height frames; on failure `error` says what failed.
    static std::unique_ptr<Resolver> create(const Device& device, const Shaders& shaders, std::uint32_t width,
                                            std::uint32_t height, std::string& error);
    ~Resolver();
    Resolver(const Resolver&) = delete;
    Resolver& operator=(const Resolver&) = delete;

    // Both resolves of `frames` (each of width x height pixels); empty on success, else what failed.
    std::string resolve(const Frames& frames, Resolved& out);

    struct State; // Vulkan objects and the functions that made them (resolve_runner.cpp)

private:
    explicit Resolver(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

// One frame of the TAAU resolve (upscale_compute, hlsl_upscale_compute) at the input size; the
// history is the last frame's output, kept on the device. Colors are RGBA floats, row-major from
// the top-left pixel.
struct UpscaleFrames {
    std::vector<float> current;    // this frame, input size (jittered)
    std::vector<float> motion;     // two per input pixel: input pixels to where that sample was last frame
    std::array<float, 2> jitter{}; // input pixel i's sample lies at i + 0.5 + jitter
    float current_weight = 0.1f;   // 1 starts the history (the first frame, a cut)
};

class Upscaler {
public:
    // The pipeline and resources for input_width x input_height frames resolved to width x height.
    static std::unique_ptr<Upscaler> create(const Device& device, const kdop::Variant& shader,
                                            std::uint32_t input_width, std::uint32_t input_height, std::uint32_t width,
                                            std::uint32_t height, std::string& error);
    ~Upscaler();
    Upscaler(const Upscaler&) = delete;
    Upscaler& operator=(const Upscaler&) = delete;

    // The resolve of `frames` into `out` (RGBA, width x height), the next frame's history; empty on
    // success, else what failed.
    std::string resolve(const UpscaleFrames& frames, std::vector<float>& out);

    struct State; // resolve_runner.cpp

private:
    explicit Upscaler(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

} // namespace engine
