#include "runtime/raster_pass.h"

#include "runtime/vulkan_error.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstring>

namespace kdop {
namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R32G32B32A32_SFLOAT, kMotionFormat = VK_FORMAT_R32G32_SFLOAT,
                   kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr VkDeviceSize kColorBytes = 16, kMotionBytes = 8, kDepthBytes = 4;

// Every attachment is cleared, kept, and left ready to be copied out; the dependencies order the
// last draw's copies before this draw's writes and this draw's writes before its copies.
Result<VkRenderPass> create_render_pass(VkDevice device) {
    std::array<VkAttachmentDescription, 3> attachments{};
    const std::array<VkFormat, 3> formats{kColorFormat, kMotionFormat, kDepthFormat};
    for (std::size_t i = 0; i < attachments.size(); ++i) {
        attachments[i].format = formats[i];
        attachments[i].samples = VK_SAMPLE_COUNT_1_BIT;
        attachments[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        attachments[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        attachments[i].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        attachments[i].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        attachments[i].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        attachments[i].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    }
    const std::array<VkAttachmentReference, 2> outputs{
        {{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}, {1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}}};
    const VkAttachmentReference depth_ref{2, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = std::uint32_t(outputs.size());
    subpass.pColorAttachments = outputs.data();
    subpass.pDepthStencilAttachment = &depth_ref;
    const VkPipelineStageFlags writes = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                        VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    const VkAccessFlags write_access =
        VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    const std::array<VkSubpassDependency, 2> dependencies{{
        {VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, writes, VK_ACCESS_TRANSFER_READ_BIT,
         write_access | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT, 0},
        {0, VK_SUBPASS_EXTERNAL, writes, VK_PIPELINE_STAGE_TRANSFER_BIT, write_access, VK_ACCESS_TRANSFER_READ_BIT, 0},
    }};
    VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rp.attachmentCount = std::uint32_t(attachments.size());
    rp.pAttachments = attachments.data();
    rp.subpassCount = 1;
    rp.pSubpasses = &subpass;
    rp.dependencyCount = std::uint32_t(dependencies.size());
    rp.pDependencies = dependencies.data();
    VkRenderPass render_pass = VK_NULL_HANDLE;
    KDOP_VK_TRY(vkCreateRenderPass(device, &rp, nullptr, &render_pass));
    return render_pass;
}

// The texture's: repeated, bilinear, without mipmaps.
Result<VkSampler> create_sampler(VkDevice device) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    info.maxLod = 0;
    VkSampler sampler = VK_NULL_HANDLE;
    KDOP_VK_TRY(vkCreateSampler(device, &info, nullptr, &sampler));
    return sampler;
}

// One attribute per location, packed in order in binding 0's records.
std::vector<VkVertexInputAttributeDescription> vertex_attributes(std::span<const std::uint32_t> attribute_floats) {
    const std::array<VkFormat, 4> format{VK_FORMAT_R32_SFLOAT, VK_FORMAT_R32G32_SFLOAT, VK_FORMAT_R32G32B32_SFLOAT,
                                         VK_FORMAT_R32G32B32A32_SFLOAT};
    std::vector<VkVertexInputAttributeDescription> attributes;
    std::uint32_t offset = 0;
    for (std::uint32_t floats : attribute_floats) {
        attributes.push_back({std::uint32_t(attributes.size()), 0, format[floats - 1], offset});
        offset += floats * 4;
    }
    return attributes;
}

// Set 0's bindings of both stages, each once (as the pipeline's layout merges them).
Result<std::vector<Kernel::Binding>> set_bindings(const Variant& vertex, const Variant& fragment) {
    std::vector<Kernel::Binding> bindings;
    for (const Variant* stage : {&vertex, &fragment})
        for (std::uint32_t i = 0; i < stage->binding_count; ++i) {
            const DescriptorBinding& b = stage->bindings[i];
            if (b.set != 0)
                return fail(fmt::format("{}: binding '{}' is in descriptor set {}; the raster pass binds set 0 only",
                                        stage->name, b.name, b.set));
            if (std::none_of(bindings.begin(), bindings.end(),
                             [&](const Kernel::Binding& seen) { return seen.binding == b.binding; }))
                bindings.push_back({b.binding, b.type, b.name, b.format});
        }
    return bindings;
}

} // namespace

Result<std::unique_ptr<RasterPass>> RasterPass::create(const Context& context, std::uint32_t width,
                                                       std::uint32_t height, const RasterPipeline& pipeline,
                                                       const Image& texture) {
    if (!(context.queue_flags() & VK_QUEUE_GRAPHICS_BIT))
        return fail(fmt::format("{} has no graphics queue to rasterize on", context.device_name()));
    if (pipeline.attribute_floats.empty()) return fail("a raster pipeline without vertex attributes");
    if (!pipeline.vertex || !pipeline.fragment) return fail("a raster pipeline without a vertex and a fragment stage");
    std::unique_ptr<RasterPass> p(new RasterPass(context));
    p->width_ = width;
    p->height_ = height;
    p->uniform_bytes_ = pipeline.uniform_bytes;
    p->clear_color_ = pipeline.clear_color;
    for (std::uint32_t floats : pipeline.attribute_floats) {
        if (floats < 1 || floats > 4) return fail(fmt::format("a vertex attribute of {} floats", floats));
        p->stride_ += floats * 4;
    }
    auto commands = OneShotCommands::create(context);
    if (!commands) return std::unexpected(commands.error());
    p->commands_ = std::move(*commands);
    if (auto ok = p->create_attachments(); !ok) return std::unexpected(ok.error());
    if (auto ok = p->create_buffers(); !ok) return std::unexpected(ok.error());
    if (auto ok = p->create_framebuffer(); !ok) return std::unexpected(ok.error());
    if (auto ok = p->create_pipeline(pipeline); !ok) return std::unexpected(ok.error());
    if (auto ok = p->create_descriptor_set(); !ok) return std::unexpected(ok.error());
    if (auto ok = p->upload_texture(texture); !ok) return std::unexpected(ok.error());
    if (auto ok = p->write_descriptor_set(); !ok) return std::unexpected(ok.error());
    return p;
}

Result<void> RasterPass::create_attachments() {
    const VkImageUsageFlags attachment = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    auto color = DeviceImage::create(context_, width_, height_, 1, kColorFormat, attachment, "the color attachment");
    if (!color) return std::unexpected(color.error());
    color_ = std::move(*color);
    auto motion = DeviceImage::create(context_, width_, height_, 1, kMotionFormat, attachment, "the motion attachment");
    if (!motion) return std::unexpected(motion.error());
    motion_ = std::move(*motion);
    auto depth = DeviceImage::create(context_, width_, height_, 1, kDepthFormat,
                                     VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                     "the depth attachment", VK_IMAGE_ASPECT_DEPTH_BIT);
    if (!depth) return std::unexpected(depth.error());
    depth_ = std::move(*depth);
    return {};
}

Result<void> RasterPass::create_buffers() {
    auto uniforms =
        DeviceBuffer::create(context_, std::max<VkDeviceSize>(uniform_bytes_, 1), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                             DeviceBuffer::Memory::host, "the raster pass's uniform block");
    if (!uniforms) return std::unexpected(uniforms.error());
    uniforms_ = std::move(*uniforms);
    const VkDeviceSize pixels = VkDeviceSize(width_) * height_;
    auto readback = DeviceBuffer::create(context_, pixels * (kColorBytes + kMotionBytes + kDepthBytes),
                                         VK_BUFFER_USAGE_TRANSFER_DST_BIT, DeviceBuffer::Memory::host,
                                         "the raster pass's read-back");
    if (!readback) return std::unexpected(readback.error());
    readback_ = std::move(*readback);
    return {};
}

Result<void> RasterPass::create_framebuffer() {
    auto render_pass = create_render_pass(context_.device());
    if (!render_pass) return std::unexpected(render_pass.error());
    render_pass_ = *render_pass;
    const std::array<VkImageView, 3> views{color_.view(), motion_.view(), depth_.view()};
    VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fb.renderPass = render_pass_;
    fb.attachmentCount = std::uint32_t(views.size());
    fb.pAttachments = views.data();
    fb.width = width_;
    fb.height = height_;
    fb.layers = 1;
    KDOP_VK_TRY(vkCreateFramebuffer(context_.device(), &fb, nullptr, &framebuffer_));
    return {};
}

// The pipeline and its layouts from what the stages reflect, by the call a renderer makes
// (kdop/vulkan_pipeline.h) and the compute passes' kernels make for theirs. What that call leaves
// to its caller is this pass's own: the vertex records, the depth test, the render pass.
Result<void> RasterPass::create_pipeline(const RasterPipeline& pipeline) {
    const Variant &vertex = *pipeline.vertex, &fragment = *pipeline.fragment;
    name_ = fmt::format("{} + {}", vertex.name, fragment.name);
    if (fragment.color_output_count != 2)
        return fail(fmt::format("{}: {} color outputs; the raster pass draws two, color and motion", fragment.name,
                                fragment.color_output_count));
    auto bindings = set_bindings(vertex, fragment);
    if (!bindings) return std::unexpected(bindings.error());
    bindings_ = std::move(*bindings);
    const VkVertexInputBindingDescription binding{0, stride_, VK_VERTEX_INPUT_RATE_VERTEX};
    const std::vector<VkVertexInputAttributeDescription> attributes = vertex_attributes(pipeline.attribute_floats);
    VkPipelineVertexInputStateCreateInfo input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    input.vertexBindingDescriptionCount = 1;
    input.pVertexBindingDescriptions = &binding;
    input.vertexAttributeDescriptionCount = std::uint32_t(attributes.size());
    input.pVertexAttributeDescriptions = attributes.data();
    GraphicsState state;
    state.vertex_input = &input;
    state.depth_test = state.depth_write = true;
    state.depth_compare = VK_COMPARE_OP_LESS;
    GraphicsTargets targets;
    targets.render_pass = render_pass_;
    const VkResult created = create_variant_graphics_pipeline(prototype_variant_functions(), context_.device(), vertex,
                                                              fragment, targets, program_, state);
    if (created != VK_SUCCESS)
        return fail(fmt::format("{}: kdop::create_variant_graphics_pipeline failed: {} ({})", name_,
                                program_.failure ? program_.failure : "", vk_result_text(created)));
    return {};
}

// One set of the pipeline's layout, from a pool sized by what the stages reflect.
Result<void> RasterPass::create_descriptor_set() {
    const ReflectedSet program = reflected_set();
    auto sets = KernelSets::create(context_, std::span(&program, 1));
    if (!sets) return std::unexpected(sets.error());
    sets_ = std::move(*sets);
    auto set = sets_.allocate(program);
    if (!set) return std::unexpected(set.error());
    set_ = *set;
    return {};
}

Result<void> RasterPass::upload_texture(const Image& texture) {
    if (texture.pixels.empty()) return fail("a raster pass's texture is empty");
    auto image =
        DeviceImage::create(context_, texture.width, texture.height, 1, kColorFormat,
                            VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "the raster pass's texture");
    if (!image) return std::unexpected(image.error());
    texture_ = std::move(*image);
    const VkDeviceSize bytes = texture.pixels.size() * sizeof(glm::vec4);
    auto staging = DeviceBuffer::create(context_, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, DeviceBuffer::Memory::host,
                                        "the raster pass's texture upload");
    if (!staging) return std::unexpected(staging.error());
    std::memcpy(staging->mapped(), texture.pixels.data(), bytes);
    auto ran = commands_->run([&](VkCommandBuffer cb) {
        image_barrier(cb, texture_.image(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                      VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {texture.width, texture.height, 1};
        vkCmdCopyBufferToImage(cb, staging->buffer(), texture_.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        image_barrier(cb, texture_.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
    });
    if (!ran) return std::unexpected(ran.error());
    return {};
}

// Binding 0 the uniform block, binding 1 the texture with its sampler; each binding's type as the
// stages reflect it.
Result<void> RasterPass::write_descriptor_set() {
    auto sampler = create_sampler(context_.device());
    if (!sampler) return std::unexpected(sampler.error());
    sampler_ = *sampler;
    const Bound bound[] = {{0, BoundBuffer{uniforms_.buffer()}},
                           {1, BoundImage{texture_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler_}}};
    return sets_.write(reflected_set(), set_, bound);
}

RasterPass::~RasterPass() {
    const VkDevice device = context_.device();
    vkDeviceWaitIdle(device);
    destroy_variant_pipeline(device, program_);
    vkDestroySampler(device, sampler_, nullptr);
    vkDestroyFramebuffer(device, framebuffer_, nullptr);
    vkDestroyRenderPass(device, render_pass_, nullptr);
}

Result<void> RasterPass::set_vertices(std::size_t slot, std::span<const std::byte> vertices) {
    if (vertices.size() % stride_ != 0 || (vertices.size() / stride_) % 3 != 0)
        return fail(fmt::format("slot {}: {} bytes are not whole triangles of {}-byte vertices", slot, vertices.size(),
                                stride_));
    if (slot >= slots_.size()) slots_.resize(slot + 1);
    Slot& s = slots_[slot];
    if (s.buffer.size() < vertices.size()) {
        auto buffer = DeviceBuffer::create(context_, vertices.size(), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                                           DeviceBuffer::Memory::host, "a raster pass's vertices");
        if (!buffer) return std::unexpected(buffer.error());
        s.buffer = std::move(*buffer);
    }
    if (!vertices.empty()) std::memcpy(s.buffer.mapped(), vertices.data(), vertices.size());
    s.vertices = std::uint32_t(vertices.size() / stride_);
    return {};
}

Result<void> RasterPass::set_uniforms(std::span<const std::byte> uniforms) {
    if (uniforms.size() != uniform_bytes_)
        return fail(fmt::format("{} bytes of uniforms for a block of {}", uniforms.size(), uniform_bytes_));
    if (!uniforms.empty()) std::memcpy(uniforms_.mapped(), uniforms.data(), uniforms.size());
    return {};
}

void RasterPass::record_draw(VkCommandBuffer cb) {
    std::array<VkClearValue, 3> clear{};
    std::memcpy(clear[0].color.float32, &clear_color_, sizeof(clear_color_));
    clear[2].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = render_pass_;
    begin.framebuffer = framebuffer_;
    begin.renderArea = {{0, 0}, {width_, height_}};
    begin.clearValueCount = std::uint32_t(clear.size());
    begin.pClearValues = clear.data();
    vkCmdBeginRenderPass(cb, &begin, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, program_.pipeline);
    const VkViewport viewport{0, 0, float(width_), float(height_), 0, 1};
    const VkRect2D scissor{{0, 0}, {width_, height_}};
    vkCmdSetViewport(cb, 0, 1, &viewport); // dynamic in every pipeline of kdop/vulkan_pipeline.h
    vkCmdSetScissor(cb, 0, 1, &scissor);
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, program_.pipeline_layout, 0, 1, &set_, 0, nullptr);
    for (const Slot& s : slots_) {
        if (s.vertices == 0) continue;
        const VkBuffer buffer = s.buffer.buffer();
        const VkDeviceSize offset = 0;
        vkCmdBindVertexBuffers(cb, 0, 1, &buffer, &offset);
        vkCmdDraw(cb, s.vertices, 1, 0, 0);
    }
    vkCmdEndRenderPass(cb);
}

Result<RasterImages> RasterPass::draw(std::span<const std::byte> uniforms) {
    if (auto ok = set_uniforms(uniforms); !ok) return std::unexpected(ok.error());
    const VkDeviceSize pixels = VkDeviceSize(width_) * height_;
    const VkDeviceSize motion_at = pixels * kColorBytes, depth_at = motion_at + pixels * kMotionBytes;
    auto ran = commands_->run([&](VkCommandBuffer cb) {
        record_draw(cb);
        VkBufferImageCopy copy{};
        copy.imageExtent = {width_, height_, 1};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        vkCmdCopyImageToBuffer(cb, color_.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer(), 1, &copy);
        copy.bufferOffset = motion_at;
        vkCmdCopyImageToBuffer(cb, motion_.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer(), 1, &copy);
        copy.bufferOffset = depth_at;
        copy.imageSubresource.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
        vkCmdCopyImageToBuffer(cb, depth_.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer(), 1, &copy);
        host_read_barrier(cb, readback_.buffer());
    });
    if (!ran) return std::unexpected(ran.error());
    RasterImages out;
    out.color = Image(width_, height_);
    out.motion.resize(pixels);
    out.depth.resize(pixels);
    const auto* bytes = static_cast<const std::byte*>(readback_.mapped());
    std::memcpy(out.color.pixels.data(), bytes, pixels * kColorBytes);
    std::memcpy(out.motion.data(), bytes + motion_at, pixels * kMotionBytes);
    std::memcpy(out.depth.data(), bytes + depth_at, pixels * kDepthBytes);
    return out;
}

Result<void> RasterPass::draw_into(std::span<const std::byte> uniforms, const RasterTargets& targets,
                                   Image* color_back) {
    if (auto ok = set_uniforms(uniforms); !ok) return ok;
    if (targets.depth && !depth_texels_.buffer()) {
        auto buffer = DeviceBuffer::create(context_, VkDeviceSize(width_) * height_ * kDepthBytes,
                                           VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                           DeviceBuffer::Memory::device, "the raster pass's depth copy");
        if (!buffer) return std::unexpected(buffer.error());
        depth_texels_ = std::move(*buffer);
    }
    auto ran = commands_->run([&](VkCommandBuffer cb) {
        record_draw(cb);
        // Every target is replaced whole: what it held, in whatever layout, is dropped.
        const VkImage filled[] = {targets.color, targets.motion, targets.depth};
        for (VkImage image : filled)
            if (image)
                image_barrier(cb, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                              VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                              VK_PIPELINE_STAGE_TRANSFER_BIT);
        VkImageCopy copy{};
        copy.srcSubresource = copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.extent = {width_, height_, 1};
        if (targets.color)
            vkCmdCopyImage(cb, color_.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, targets.color,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        if (color_back) {
            VkBufferImageCopy texels{};
            texels.imageExtent = {width_, height_, 1};
            texels.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            vkCmdCopyImageToBuffer(cb, color_.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer(), 1,
                                   &texels);
            host_read_barrier(cb, readback_.buffer());
        }
        if (targets.motion)
            vkCmdCopyImage(cb, motion_.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, targets.motion,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        if (targets.depth) {
            VkBufferImageCopy texels{};
            texels.imageExtent = {width_, height_, 1};
            texels.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
            vkCmdCopyImageToBuffer(cb, depth_.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, depth_texels_.buffer(), 1,
                                   &texels);
            VkMemoryBarrier written{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
            written.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
            written.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
            vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &written, 0,
                                 nullptr, 0, nullptr);
            texels.imageSubresource.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
            vkCmdCopyBufferToImage(cb, depth_texels_.buffer(), targets.depth, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                                   &texels);
        }
        for (VkImage image : filled)
            if (image)
                image_barrier(cb, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                              VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                              VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
    });
    if (!ran) return std::unexpected(ran.error());
    if (color_back) {
        *color_back = Image(width_, height_);
        std::memcpy(color_back->pixels.data(), readback_.mapped(), VkDeviceSize(width_) * height_ * kColorBytes);
    }
    return {};
}

} // namespace kdop
