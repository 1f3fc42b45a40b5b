// Rasterization beside the compute passes: one graphics pipeline (a vertex and a fragment stage,
// depth test) drawing triangle lists into three attachments, read back after each draw: color
// (rgba32f, fragment output 0), motion (rg32f, output 1) and depth (d32, 0 at the near plane).
// What a renderer hands its TAA resolve, made on lavapipe: the 3-D testbed (testbed/) draws its
// scenes with it.
//
// The stages come as registry entries (kdop/variant.h), and the pipeline, its layout, the
// descriptor set and its writes from what they reflect, through the same calls as the compute
// passes' (kdop/vulkan_pipeline.h, runtime/kernel_sets.h). The shaders see one uniform block (set 0,
// binding 0) and one texture (binding 1: a sampler2DArray of one layer, rgba32f, repeated,
// bilinear, without mipmaps, so that a minified texture aliases as a renderer's distant detail does
// without them). Vertices are `stride`-byte records whose attributes (locations 0, 1, ...) are
// packed in order, each 1 to 4 floats. Back faces are drawn too. Every Vulkan call is checked.
#pragma once

#include "core/result.h"
#include "images/image.h"
#include "runtime/context.h"
#include "runtime/device_buffer.h"
#include "runtime/device_image.h"
#include "runtime/kernel_sets.h"
#include "runtime/one_shot_commands.h"

#include <kdop/variant.h>
#include <kdop/vulkan_pipeline.h>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace kdop {

struct RasterPipeline {
    // The stages with what they reflect (their bindings in set 0); needed only while the pass is made.
    const Variant* vertex = nullptr;
    const Variant* fragment = nullptr;           // two color outputs: color and motion
    std::vector<std::uint32_t> attribute_floats; // per location: 1 to 4 floats
    std::uint32_t uniform_bytes = 0;             // the uniform block's size
    glm::vec4 clear_color{0, 0, 0, 1};           // where nothing is drawn
};

// One draw's attachments, read back.
struct RasterImages {
    Image color;                   // rgba
    std::vector<glm::vec2> motion; // row-major
    std::vector<float> depth;      // row-major; 1 where nothing is drawn
};

// Images a draw's attachments are copied into on the device (RasterPass::draw_into), each of the
// pass's size and made for transfers into it and sampling; left in
// VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL for a compute pass to sample (RectifyPass::images_to_fill).
struct RasterTargets {
    VkImage color = VK_NULL_HANDLE;  // rgba32f, or null: not copied
    VkImage motion = VK_NULL_HANDLE; // rg32f, or null: not copied
    VkImage depth = VK_NULL_HANDLE;  // r32f, or null: not copied
};

class RasterPass {
public:
    // A pass drawing width x height images with `pipeline`, sampling `texture`.
    static Result<std::unique_ptr<RasterPass>> create(const Context& context, std::uint32_t width, std::uint32_t height,
                                                      const RasterPipeline& pipeline, const Image& texture);
    ~RasterPass();
    RasterPass(const RasterPass&) = delete;
    RasterPass& operator=(const RasterPass&) = delete;

    // The triangle list of slot `slot` (0, 1, ...): whole vertices of the pipeline's stride, kept
    // on the device until the slot is set again. Every slot set is drawn, in slot order.
    Result<void> set_vertices(std::size_t slot, std::span<const std::byte> vertices);
    // Clears, draws every slot with `uniforms` (the uniform block's bytes) and reads the
    // attachments back.
    Result<RasterImages> draw(std::span<const std::byte> uniforms);
    // The same draw, its attachments copied into `targets` on the device instead of read back: a
    // frame a compute pass takes from there (the TAA resolve's inputs), the same floats. With
    // `color_back`, the color alone is also read back into it (what a measurement compares with).
    Result<void> draw_into(std::span<const std::byte> uniforms, const RasterTargets& targets,
                           Image* color_back = nullptr);

private:
    explicit RasterPass(const Context& context) : context_(context) {}
    Result<void> create_attachments();
    Result<void> create_buffers();
    Result<void> create_framebuffer();
    Result<void> create_pipeline(const RasterPipeline& pipeline);
    Result<void> create_descriptor_set();
    Result<void> upload_texture(const Image& texture);
    Result<void> write_descriptor_set();
    // The descriptor set's reflected interface: what KernelSets allocates and writes by.
    ReflectedSet reflected_set() const { return {name_, program_.set_layouts[0], bindings_}; }
    Result<void> set_uniforms(std::span<const std::byte> uniforms);
    // Clears the attachments and draws every slot, leaving them ready to be copied from.
    void record_draw(VkCommandBuffer cb);

    const Context& context_;
    std::uint32_t width_ = 0, height_ = 0, stride_ = 0, uniform_bytes_ = 0;
    DeviceImage color_, motion_, depth_, texture_;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
    VkSampler sampler_ = VK_NULL_HANDLE;
    std::string name_;                      // "<vertex> + <fragment>", the stages' names
    VariantPipeline program_;               // set layout, pipeline layout and pipeline, as reflected
    std::vector<Kernel::Binding> bindings_; // set 0's, of both stages
    KernelSets sets_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    glm::vec4 clear_color_{0};
    DeviceBuffer uniforms_, readback_; // host-visible
    // Depth on its way into a color image (draw_into): Vulkan copies no depth image into a color
    // one, so it goes through a buffer. Made at the first draw that copies depth.
    DeviceBuffer depth_texels_;
    struct Slot {
        DeviceBuffer buffer; // host-visible; grown, never shrunk
        std::uint32_t vertices = 0;
    };
    std::vector<Slot> slots_;
    std::unique_ptr<OneShotCommands> commands_;
};

} // namespace kdop
