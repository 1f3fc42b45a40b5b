// The GPU side of one rectification: named input textures (rgba32f or rgba16f; by default the
// current and history frames of shader_templates/rectify.comp.in), an rgba32f output, and the
// buffers to fill and read them. Created once per image size and input format; any number of
// kernels can then be dispatched on the uploaded inputs, which is what the benchmarks do. The TAA
// resolve (temporal/taa_resolve.h) uses the same pass with its color, history, motion and depth.
// rectify() below does the whole round trip for one variant.
#pragma once

#include "images/image.h"
#include "runtime/context.h"
#include "runtime/device_buffer.h"
#include "runtime/kernel.h"
#include "runtime/kernel_sets.h"
#include "runtime/one_shot_commands.h"
#include "runtime/texture_format.h"

#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

// An input texture: its name in the kernels, its channels (1, 2 or 4; fewer than four in rgba32f
// passes only) of the pass's format, and its size, the pass's (the output's) unless given. A
// motion field needs two channels and a depth one, so a frame drawn on the device copies into them
// as it is; an upscaling resolve's frame is smaller than its output and history.
struct PassInput {
    std::string name;
    std::uint32_t channels = 4;
    std::uint32_t width = 0, height = 0; // 0: the pass's
};

struct DispatchTiming {
    double wall_ms;   // submit to fence, as a caller waits for it
    double device_ms; // between timestamps around the dispatch; NaN where the queue has none
};

class RectifyPass {
public:
    // Inputs current_frame and history_frame.
    static Result<std::unique_ptr<RectifyPass>> create(const Context& context, uint32_t width, uint32_t height,
                                                       TextureFormat format);
    // Inputs of these names, each a combined image sampler in the kernels dispatched.
    static Result<std::unique_ptr<RectifyPass>> create(const Context& context, uint32_t width, uint32_t height,
                                                       TextureFormat format, std::vector<std::string> inputs);
    // Inputs of these names and channels.
    static Result<std::unique_ptr<RectifyPass>> create(const Context& context, uint32_t width, uint32_t height,
                                                       TextureFormat format, std::vector<PassInput> inputs);
    ~RectifyPass();
    RectifyPass(const RectifyPass&) = delete;
    RectifyPass& operator=(const RectifyPass&) = delete;

    // Both images must have the pass's size.
    Result<void> upload(const Image& current, const Image& history);
    // One image per input, in the order create() named them, each of its input's size; a null one
    // is not uploaded, and a kernel that reads an input never uploaded is refused. An input of fewer
    // than four channels takes each pixel's first ones.
    Result<void> upload(std::span<const Image* const> images);
    // Input `name` from `texels`: each pixel's channels as floats, row-major, as the input holds
    // them (a motion field's two, a depth's one). rgba32f passes.
    Result<void> upload(std::string_view name, std::span<const float> texels);
    // One dispatch of `kernel` over the whole image; `gamma` goes to kernels with a push constant.
    Result<DispatchTiming> dispatch(const Kernel& kernel, float gamma);
    // The same for any kernel with the pass's bindings (its inputs and the rectified_history
    // storage image), a project's own shader included: every push-constant member gets the value
    // of its name, as floats; a missing or extra value is an error.
    struct PushConstantValue {
        PushConstantValue(std::string name, std::vector<float> values)
            : name(std::move(name)), values(std::move(values)) {}
        // A member's words as they are: a uint's (a frame index, a flag), or any value's bits.
        static PushConstantValue words(std::string name, std::vector<std::uint32_t> words) {
            PushConstantValue v(std::move(name), {});
            v.uints = std::move(words);
            return v;
        }
        std::string name;
        std::vector<float> values;
        std::vector<std::uint32_t> uints; // instead of values
    };
    Result<DispatchTiming> dispatch(const Kernel& kernel, std::span<const PushConstantValue> values);
    // The same for a kernel whose bindings are named otherwise: a renderer's own resolve, bound by
    // role (temporal/resolve_bindings.h). Each of `as` names one of the kernel's bindings and what
    // it gets: an input's name, kOutput (the storage image written) or kSampler (for a separate
    // texture's sampler). A binding `as` does not name gets the input of its own name. Every
    // sampler is then linear and clamped to the edge, as a renderer's texture() reads expect; kdop's
    // own kernels read with texelFetch, where the sampler does nothing.
    struct BindingAs {
        std::string_view binding, input;
    };
    static constexpr std::string_view kOutput = "rectified_history", kSampler = "(sampler)";
    // A uniform block's bytes for this dispatch (its binding's name, the block's whole size),
    // copied into a buffer the pass keeps for that binding.
    struct UniformBlock {
        std::string_view binding;
        std::span<const std::byte> bytes;
    };
    Result<DispatchTiming> dispatch(const Kernel& kernel, std::span<const PushConstantValue> values,
                                    std::span<const BindingAs> as, std::span<const UniformBlock> uniforms = {});
    // The output of the last dispatch, as floats (an rgba16f output's halves, exactly).
    Result<Image> download();

    // State a caller keeps on the device between dispatches, per kernel: input `name` gets `count`
    // textures ("slots"), cleared to zero, and uploads and dispatches use the selected one (slot 0
    // at first). The TAA resolve keeps each shader's history so.
    Result<void> add_slots(std::string_view name, std::size_t count);
    Result<void> select_slot(std::string_view name, std::size_t slot);
    // Copies the last dispatch's output into input `name`'s selected texture, on the device; the
    // output stays for download(). The next frame's history, with no round trip through the host.
    // An output the kernel declared rgba16f (a renderer's history format) is converted, exactly.
    Result<void> copy_output_to(std::string_view name);
    // The selected textures of the inputs named, in that order, for another pass on the same device
    // to fill with its own commands (a frame drawn there: RasterPass::draw_into), never through
    // the host. Whatever fills them replaces every texel and leaves them in
    // VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, where dispatches sample them; each then counts as
    // uploaded. rgba32f passes only, whose inputs are the formats a draw's attachments copy into.
    Result<std::vector<VkImage>> images_to_fill(std::span<const std::string_view> names);
    // The selected texture of input `name`, for another pass on the same queue to sample between
    // this one's commands, in VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: what was uploaded, filled or
    // copied there (copy_output_to; the TAA resolve's outputs, measured where they are). An input
    // never filled is refused.
    Result<VkImageView> view_to_sample(std::string_view name);

private:
    struct Texture {
        VkImage image = VK_NULL_HANDLE;
        VkDeviceMemory memory = VK_NULL_HANDLE;
        VkImageView view = VK_NULL_HANDLE;
    };
    explicit RectifyPass(const Context& context) : context_(context) {}
    Result<void> allocate(const VkMemoryRequirements& req, VkMemoryPropertyFlags flags, VkDeviceMemory& memory);
    Result<void> create_texture(Texture& t, VkFormat format, VkImageUsageFlags usage, uint32_t width, uint32_t height);
    void output_to_transfer_source(VkCommandBuffer cb);
    // The texture the last dispatch wrote: output_, or half_output_ for a kernel that declared its
    // storage image rgba16f.
    const Texture& written() const { return half_written_ ? half_output_ : output_; }
    void destroy(Texture& t);

    const Context& context_;
    uint32_t width_ = 0, height_ = 0;
    TextureFormat format_ = TextureFormat::rgba32f;
    struct Input {
        std::string name;
        std::uint32_t channels = 4;
        uint32_t width = 0, height = 0;
        std::vector<Texture> slots; // one, or add_slots()'s
        std::size_t selected = 0;
        bool uploaded = false;
        const Texture& texture() const { return slots[selected]; }
    };
    Result<Input*> input(std::string_view name);
    // Where each input lies in the upload buffer, in create()'s order.
    std::vector<VkDeviceSize> upload_offsets() const;
    // Copies the inputs marked in `which` (by index) from the upload buffer into their textures.
    Result<void> copy_uploads(const std::vector<bool>& which);
    std::vector<Input> inputs_;
    Texture output_;
    Texture half_output_;       // made when a kernel first writes rgba16f
    bool half_written_ = false; // the last dispatch wrote half_output_
    // Where the output is after the last command: GENERAL after a dispatch, TRANSFER_SRC_OPTIMAL
    // after a copy or a download.
    VkImageLayout output_layout_ = VK_IMAGE_LAYOUT_UNDEFINED;
    DeviceBuffer upload_, readback_;            // host-visible
    VkSampler sampler_ = VK_NULL_HANDLE;        // nearest: kdop's kernels, which read with texelFetch
    VkSampler linear_sampler_ = VK_NULL_HANDLE; // dispatches with bindings `as`
    KernelSets kernel_sets_;                    // one set, written afresh for each dispatch's kernel
    // A uniform block's buffer by binding name, made when first given: written before each
    // dispatch, which the pass waits for, so one buffer per block serves every dispatch.
    std::map<std::string, DeviceBuffer, std::less<>> uniform_buffers_;
    std::unique_ptr<OneShotCommands> commands_;
    VkQueryPool timestamps_ = VK_NULL_HANDLE; // null where the queue cannot time
    bool dispatched_ = false;                 // the output holds a dispatch's result
};

// Loads `variant`, runs it once on the pair and reads the result back.
Result<Image> rectify(const Context& context, const Variant& variant, const Image& current, const Image& history,
                      TextureFormat format, float gamma);

} // namespace kdop
