// LDR-FLIP and HDR-FLIP on the device: the arithmetic of flip.h and hdr_flip.h, in the same order,
// as Vulkan compute passes (shader_templates/flip.comp.in) on any device, lavapipe included.
// The CPU classes stay the reference this one is tested against (tests/device_flip_test.cpp):
// per-pixel maps within 1e-5, means within 1e-6 relative.
//
// Per evaluation both images are uploaded once (or kept: a reference unchanged since the pair
// before, an output loaded on the device); everything after runs on the device in one submission:
// per exposure (one for LDR-FLIP) the color transform with the horizontal filters, the vertical
// filters and the error, kept as each pixel's largest over the exposures; then each row's sum,
// compensated in float. What comes back is one float per row (the mean, summed in double), and the
// maps only when asked for. The kernels are made once per ppd, the buffers once per size.
//
// Not thread-safe: one object is one set of device buffers. Not copyable.
#pragma once

#include "core/result.h"
#include "flip/device_flip_passes.h"
#include "flip/flip.h"
#include "flip/hdr_flip.h"
#include "images/image.h"
#include "runtime/context.h"
#include "runtime/device_buffer.h"
#include "runtime/device_image.h"
#include "runtime/kernel.h"
#include "runtime/kernel_sets.h"
#include "runtime/one_shot_commands.h"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace kdop {

class RunnableVariant;

class DeviceFlip {
public:
    // Compiles the passes for `pixels_per_degree` (check_pixels_per_degree's range) and allocates
    // the buffers and images of a width x height pair (112 bytes a pixel, checked against the
    // device's buffer, texel buffer, image and dispatch limits, each named in the error).
    static Result<std::unique_ptr<DeviceFlip>> create(const Context& context, double pixels_per_degree,
                                                      std::uint32_t width, std::uint32_t height);
    ~DeviceFlip();
    DeviceFlip(const DeviceFlip&) = delete;
    DeviceFlip& operator=(const DeviceFlip&) = delete;

    double pixels_per_degree() const { return ppd_; }
    const Context& context() const { return context_; }
    std::uint32_t width() const { return width_; }
    std::uint32_t height() const { return height_; }

    // Device memory a width x height pair takes.
    static std::uint64_t bytes(std::uint32_t width, std::uint32_t height);
    // Whether `context` can hold a width x height pair: its dispatch, texel buffer, storage buffer
    // and image limits, each named in the error. What create() checks first, without compiling or
    // allocating anything, so a command can refuse a size before its work.
    static Result<void> check_limits(const Context& context, std::uint32_t width, std::uint32_t height);

    // A name the caller gives a reference's pixels, for the work an evaluation can keep: a nonzero
    // key promises that every image given with it holds the same pixels (temporal/output_store.h
    // gives each image it holds a key of its own). FLIP never reads back what it uploaded, which on
    // a GPU lies in uncached memory, so only the caller can vouch for that. Where an evaluation's
    // reference has the key of the one before, its upload, its range check and its half of the
    // horizontal pass are kept from that one, when that one left them: one exposure (LDR-FLIP, or
    // HDR-FLIP over a range of one), the same exposure and tone mapper, and no evaluation or load
    // of another reference in between. Every variant's ghosting on a frame is measured against
    // the same reference (temporal/taa_measure.h). The figures are the same bits either way.
    using ReferenceKey = std::uint64_t;
    static constexpr ReferenceKey kNoKey = 0;

    // LDR-FLIP as LdrFlip computes it: linear RGB in [0, 1], both of the object's size; anything
    // else is an error naming the image, the pixel and the value, as LdrFlip's.
    Result<double> mean(const Image& reference, const Image& test);
    // The mean and, with `read_map`, the error map (LdrFlip::error_map's): the one map the mean
    // is taken of, read back instead of computed again.
    Result<FlipMap> ldr(const Image& reference, const Image& test, bool read_map, ReferenceKey key = kNoKey);
    Result<FlipTerms> terms(const Image& reference, const Image& test);

    // HDR-FLIP as HdrFlip::maps computes it (inputs and range checked the same way). With
    // `read_maps` false only `range` and `mean` are filled: nothing per pixel comes back.
    Result<HdrFlipMaps> hdr(const Image& reference, const Image& test, const ExposureOptions& options,
                            bool read_maps = true, ReferenceKey key = kNoKey);

    // ---- A pair loaded on the device: a TAA resolve's outputs measured where they are ----

    // One image of the pair.
    enum class Input { reference, test };
    // Where a loaded image lay outside its range: how many pixels, and the first in row-major
    // order with its value as it was.
    struct Outside {
        std::uint64_t count = 0;
        std::uint32_t x = 0, y = 0;
        glm::vec4 value{};
    };
    // Loads `input` from `source`, an rgba32f texture of the object's size on the same context's
    // queue, which another pass left in VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL (a resolve's output,
    // temporal/taa_resolve.h), with no trip through the host: each value within `rounding` of the
    // range, [0, 1] or with `hdr` [0, inf), moved onto it (within_range's rule, temporal/taa_measure.h),
    // and where any lies further, what Outside says (nullopt where none does).
    Result<std::optional<Outside>> load(Input input, VkImageView source, bool hdr, float rounding);
    // The loaded image, read from the inputs (for what the host shows of a frame).
    Image loaded(Input input) const;
    // Bytes of one image of the pair, as store() and restore() copy it.
    std::uint64_t image_bytes() const { return std::uint64_t(width_) * height_ * 16; }
    // Copies the loaded `input` into `buffer` (image_bytes() or more, a transfer destination), or
    // `buffer` into `input`: an image the caller keeps on the device to measure again (a resolve's
    // previous output, temporal/output_store.h).
    Result<void> store(Input input, const DeviceBuffer& buffer);
    Result<void> restore(const DeviceBuffer& buffer, Input input);
    // LDR-FLIP of `test` against `reference`, each uploaded from the host or, where null, as loaded
    // on the device (not checked again: load() checked it).
    Result<FlipMap> ldr(const Image* reference, const Image* test, bool read_map, ReferenceKey key = kNoKey);
    // HDR-FLIP likewise. The exposure range's luminances of an image that is on the device alone
    // are found there (luminances()); those of one from the host, where it came from.
    Result<HdrFlipMaps> hdr(const Image* reference, const Image* test, const ExposureOptions& options, bool read_maps,
                            ReferenceKey key = kNoKey);
    // luminances_of (flip/hdr_flip.h) of the image in `input` (uploaded by the last evaluation, or
    // loaded), to the bit: its largest luminance and counts of its luminances' bits come back (256
    // KiB, two to four times), not the image.
    Result<Luminances> luminances(Input input);

private:
    DeviceFlip(const Context& context, double ppd, std::uint32_t width, std::uint32_t height);

    // One exposure: 2^exposure and its place in the exposure map; no tone mapper for LDR-FLIP.
    struct Exposure {
        float scale = 1, where = 0;
    };
    struct Evaluation {
        double mean = 0;
        std::vector<float> error, exposure, color, feature; // filled when asked for
    };
    enum class ReadBack { mean, error, error_and_exposure, terms };
    // The copy store() (`into_buffer`) and restore() make, between `input` and `buffer`.
    Result<void> copy(Input input, const DeviceBuffer& buffer, bool into_buffer);
    // HDR-FLIP over `range`, the images as evaluate() takes them.
    Result<HdrFlipMaps> hdr_over(const Image* reference, const Image* test, const ExposureRange& range,
                                 ToneMapper tone_mapper, bool read_maps, ReferenceKey key);
    // Null images are as loaded on the device.
    Result<Evaluation> evaluate(const Image* reference, const Image* test, std::optional<ToneMapper> tone_mapper,
                                std::span<const Exposure> exposures, ReadBack read_back, ReferenceKey key);
    // Both images of the object's size, their values accepted by `check_values` (the reference
    // once: not again where it is kept; a null image is as loaded on the device, checked then).
    Result<void> check_pair(const Image* reference, const Image* test,
                            Result<void> (*check_values)(const Image&, const std::string&), ReferenceKey key) const;

    const Context& context_;
    double ppd_;
    std::uint32_t width_, height_;
    static constexpr int kHorizontal = kFlipHorizontal, kVertical = kFlipVertical, kRowSums = kFlipRowSums,
                         kLoad = kFlipLoad, kLuminance = kFlipLuminance, kPasses = kFlipPasses;
    std::array<std::unique_ptr<RunnableVariant>, kPasses> shaders_;
    std::array<std::unique_ptr<Kernel>, kPasses> kernels_;
    std::array<VkDescriptorSet, kPasses> sets_{};
    KernelSets kernel_sets_;
    // Pixels per invocation of the horizontal and the vertical pass (flip_run_length).
    std::array<std::uint32_t, 2> runs_{1, 1};
    DeviceBuffer inputs_, maps_, row_sums_, outside_, histogram_;
    VkSampler sampler_ = VK_NULL_HANDLE;        // load()'s source, fetched texel by texel
    VkBufferView inputs_view_ = VK_NULL_HANDLE; // the inputs as the texel buffer the passes fetch from
    DeviceImage horizontal_;
    // What the reference's planes in horizontal_ hold after an evaluation of one exposure: which
    // reference (by its key) at which exposure and tone mapper; nullopt after any other.
    struct ReferencePlanes {
        ReferenceKey key = kNoKey;
        float exposure_scale = 1;
        std::uint32_t tone_mapper = 0;
    };
    std::optional<ReferencePlanes> reference_planes_;
    std::unique_ptr<OneShotCommands> commands_;
};

} // namespace kdop
