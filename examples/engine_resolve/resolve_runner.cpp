// See resolve_runner.h. Plain Vulkan 1.0 on purpose: what an engine would write around kdop's helper,
// and nothing kdop-specific beyond kdop/vulkan_pipeline.h and the registry entries.
#include "resolve_runner.h"

#include <kdop/resolve_runner.h>
#include <kdop/vulkan_pipeline.h>

#include <cstring>
#include <functional>
#include <string>
#include <tuple>
#include <utility>

namespace engine {

// Device-level entry points this file calls beyond kdop's own table.
// clang-format off
#define ENGINE_DEVICE_FUNCTIONS(X) \
    X(vkCreateBuffer) X(vkDestroyBuffer) X(vkGetBufferMemoryRequirements) X(vkBindBufferMemory) \
    X(vkAllocateMemory) X(vkFreeMemory) X(vkMapMemory) \
    X(vkCreateImage) X(vkDestroyImage) X(vkGetImageMemoryRequirements) X(vkBindImageMemory) \
    X(vkCreateImageView) X(vkDestroyImageView) X(vkCreateSampler) X(vkDestroySampler) \
    X(vkCreateRenderPass) X(vkDestroyRenderPass) X(vkCreateFramebuffer) X(vkDestroyFramebuffer) \
    X(vkCreateCommandPool) X(vkDestroyCommandPool) X(vkAllocateCommandBuffers) X(vkResetCommandBuffer) \
    X(vkBeginCommandBuffer) X(vkEndCommandBuffer) X(vkCmdPipelineBarrier) \
    X(vkCmdCopyBufferToImage) X(vkCmdCopyImageToBuffer) X(vkCmdBindPipeline) X(vkCmdBindDescriptorSets) \
    X(vkCmdPushConstants) X(vkCmdDispatch) X(vkCmdBeginRenderPass) X(vkCmdEndRenderPass) X(vkCmdDraw) \
    X(vkCmdSetViewport) X(vkCmdSetScissor) X(vkUpdateDescriptorSets) \
    X(vkQueueSubmit) X(vkQueueWaitIdle) X(vkDeviceWaitIdle)
// clang-format on

struct DeviceFunctions {
#define ENGINE_DECLARE(name) PFN_##name name = nullptr;
    ENGINE_DEVICE_FUNCTIONS(ENGINE_DECLARE)
#undef ENGINE_DECLARE
};

// What the shaders' host side must agree with: the reflected block sizes are checked against these.
struct ComputeParameters { // resolve_compute.comp's ResolveParameters (std140)
    float motion[2];
    float current_weight;
};
struct FragmentParameters { // resolve_fragment.frag's ResolveParameters
    float motion[2];
};

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    void* mapped = nullptr; // host-visible, coherent, mapped for the resolver's life
};
struct Texture {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
};

// What each resolver here holds: the device, the functions it calls, what to destroy, and the
// helpers that make its resources.
struct Vulkan {
    Device device;
    DeviceFunctions fn;
    kdop::VariantVulkanFunctions kdop_fn;
    VkPhysicalDeviceMemoryProperties memory{};
    std::vector<std::function<void()>> cleanup; // run in reverse by destroy()
    VkCommandBuffer commands = VK_NULL_HANDLE;

    // Destroys what was made, newest first. The derived states call it from their destructors,
    // while the members the cleanup refers to (the pipelines) still exist.
    void destroy() {
        if (device.device && fn.vkDeviceWaitIdle) fn.vkDeviceWaitIdle(device.device);
        for (auto it = cleanup.rbegin(); it != cleanup.rend(); ++it) (*it)();
        cleanup.clear();
    }

    // The device's functions, through vkGetDeviceProcAddr.
    std::string load_functions() {
        const VkDevice d = device.device;
        const auto get_device_proc_addr = reinterpret_cast<PFN_vkGetDeviceProcAddr>(
            device.get_instance_proc_addr(device.instance, "vkGetDeviceProcAddr"));
        const auto get_memory_properties = reinterpret_cast<PFN_vkGetPhysicalDeviceMemoryProperties>(
            device.get_instance_proc_addr(device.instance, "vkGetPhysicalDeviceMemoryProperties"));
        if (!get_device_proc_addr || !get_memory_properties) return "the instance lacks a Vulkan 1.0 entry point";
        if (kdop::load_variant_functions(d, get_device_proc_addr, kdop_fn) != VK_SUCCESS)
            return "kdop::load_variant_functions: the device lacks an entry point";
#define ENGINE_LOAD(name)                                                                                              \
    fn.name = reinterpret_cast<PFN_##name>(get_device_proc_addr(d, #name));                                            \
    if (!fn.name) return "the device lacks " #name;
        ENGINE_DEVICE_FUNCTIONS(ENGINE_LOAD)
#undef ENGINE_LOAD
        get_memory_properties(device.physical_device, &memory);
        return {};
    }

    // One command buffer, reset and recorded for each submission.
    std::string create_command_buffer() {
        const VkDevice d = device.device;
        VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool_info.queueFamilyIndex = device.queue_family;
        VkCommandPool pool = VK_NULL_HANDLE;
        if (auto e = check(fn.vkCreateCommandPool(d, &pool_info, nullptr, &pool), "vkCreateCommandPool"); !e.empty())
            return e;
        cleanup.push_back([this, pool] { fn.vkDestroyCommandPool(device.device, pool, nullptr); });
        VkCommandBufferAllocateInfo allocate_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        allocate_info.commandPool = pool;
        allocate_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        allocate_info.commandBufferCount = 1;
        return check(fn.vkAllocateCommandBuffers(d, &allocate_info, &commands), "vkAllocateCommandBuffers");
    }

    std::string check(VkResult result, const char* what) const {
        return result == VK_SUCCESS ? std::string() : std::string(what) + " failed: VkResult " + std::to_string(result);
    }

    std::string allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags flags, VkDeviceMemory& out) {
        std::uint32_t type = 0;
        while (type < memory.memoryTypeCount && !((requirements.memoryTypeBits >> type & 1u) &&
                                                  (memory.memoryTypes[type].propertyFlags & flags) == flags))
            ++type;
        if (type == memory.memoryTypeCount) return "no memory type for a resource";
        VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        info.allocationSize = requirements.size;
        info.memoryTypeIndex = type;
        if (auto e = check(fn.vkAllocateMemory(device.device, &info, nullptr, &out), "vkAllocateMemory"); !e.empty())
            return e;
        cleanup.push_back([this, out] { fn.vkFreeMemory(device.device, out, nullptr); });
        return {};
    }

    std::string create_buffer(Buffer& b, VkDeviceSize size, VkBufferUsageFlags usage) {
        VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        info.size = size;
        info.usage = usage;
        if (auto e = check(fn.vkCreateBuffer(device.device, &info, nullptr, &b.buffer), "vkCreateBuffer"); !e.empty())
            return e;
        cleanup.push_back([this, buffer = b.buffer] { fn.vkDestroyBuffer(device.device, buffer, nullptr); });
        VkMemoryRequirements requirements;
        fn.vkGetBufferMemoryRequirements(device.device, b.buffer, &requirements);
        VkDeviceMemory memory_object = VK_NULL_HANDLE;
        const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        if (auto e = allocate(requirements, host, memory_object); !e.empty()) return e;
        if (auto e = check(fn.vkBindBufferMemory(device.device, b.buffer, memory_object, 0), "vkBindBufferMemory");
            !e.empty())
            return e;
        return check(fn.vkMapMemory(device.device, memory_object, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
    }

    std::string create_texture(Texture& t, VkFormat format, VkImageUsageFlags usage, std::uint32_t width,
                               std::uint32_t height) {
        VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        info.imageType = VK_IMAGE_TYPE_2D;
        info.format = format;
        info.extent = {width, height, 1};
        info.mipLevels = 1;
        info.arrayLayers = 1;
        info.samples = VK_SAMPLE_COUNT_1_BIT;
        info.tiling = VK_IMAGE_TILING_OPTIMAL;
        info.usage = usage;
        info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        if (auto e = check(fn.vkCreateImage(device.device, &info, nullptr, &t.image), "vkCreateImage"); !e.empty())
            return e;
        cleanup.push_back([this, image = t.image] { fn.vkDestroyImage(device.device, image, nullptr); });
        VkMemoryRequirements requirements;
        fn.vkGetImageMemoryRequirements(device.device, t.image, &requirements);
        VkDeviceMemory memory_object = VK_NULL_HANDLE;
        if (auto e = allocate(requirements, 0, memory_object); !e.empty()) return e;
        if (auto e = check(fn.vkBindImageMemory(device.device, t.image, memory_object, 0), "vkBindImageMemory");
            !e.empty())
            return e;
        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view.image = t.image;
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = format;
        view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        if (auto e = check(fn.vkCreateImageView(device.device, &view, nullptr, &t.view), "vkCreateImageView");
            !e.empty())
            return e;
        cleanup.push_back([this, v = t.view] { fn.vkDestroyImageView(device.device, v, nullptr); });
        return {};
    }

    std::string create_sampler(VkSampler& out, VkFilter filter) {
        VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        info.magFilter = info.minFilter = filter;
        info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
        info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        if (auto e = check(fn.vkCreateSampler(device.device, &info, nullptr, &out), "vkCreateSampler"); !e.empty())
            return e;
        cleanup.push_back([this, out] { fn.vkDestroySampler(device.device, out, nullptr); });
        return {};
    }

    void barrier(VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags src_access,
                 VkAccessFlags dst_access, VkPipelineStageFlags src_stage, VkPipelineStageFlags dst_stage) {
        VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        b.srcAccessMask = src_access;
        b.dstAccessMask = dst_access;
        b.oldLayout = from;
        b.newLayout = to;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        fn.vkCmdPipelineBarrier(commands, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
    }

    // Records the command buffer afresh with `record`, submits it and waits for it.
    template <class Record>
    std::string run_once(Record record) {
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        if (auto e = check(fn.vkResetCommandBuffer(commands, 0), "vkResetCommandBuffer"); !e.empty()) return e;
        if (auto e = check(fn.vkBeginCommandBuffer(commands, &begin), "vkBeginCommandBuffer"); !e.empty()) return e;
        record();
        if (auto e = check(fn.vkEndCommandBuffer(commands), "vkEndCommandBuffer"); !e.empty()) return e;
        return submit();
    }

    // Submits the recorded command buffer and waits for it.
    std::string submit() {
        VkSubmitInfo submit_info{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit_info.commandBufferCount = 1;
        submit_info.pCommandBuffers = &commands;
        if (auto e = check(fn.vkQueueSubmit(device.queue, 1, &submit_info, VK_NULL_HANDLE), "vkQueueSubmit");
            !e.empty())
            return e;
        return check(fn.vkQueueWaitIdle(device.queue), "vkQueueWaitIdle");
    }
};

struct Resolver::State : Vulkan {
    Shaders shaders;
    std::uint32_t width = 0, height = 0;

    Buffer upload, readback, compute_parameters, fragment_parameters, clip_distances;
    Texture current, history, compute_output, fragment_output;
    VkSampler nearest = VK_NULL_HANDLE, linear = VK_NULL_HANDLE;
    VkRenderPass render_pass = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    kdop::VariantPipeline compute_pipeline, graphics_pipeline;
    VkDescriptorSet compute_sets[kdop::kMaxVariantDescriptorSets] = {};
    VkDescriptorSet graphics_sets[kdop::kMaxVariantDescriptorSets] = {};

    ~State() { destroy(); }

    std::size_t image_bytes() const { return std::size_t(width) * height * 4 * sizeof(float); }

    // A color target for the fragment resolve, left ready to be copied out.
    std::string create_render_pass() {
        VkAttachmentDescription color{};
        color.format = VK_FORMAT_R32G32B32A32_SFLOAT;
        color.samples = VK_SAMPLE_COUNT_1_BIT;
        color.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE; // every pixel is drawn
        color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        color.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        color.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        VkSubpassDescription subpass{};
        subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        subpass.colorAttachmentCount = 1;
        subpass.pColorAttachments = &reference;
        VkSubpassDependency to_copy{};
        to_copy.srcSubpass = 0;
        to_copy.dstSubpass = VK_SUBPASS_EXTERNAL;
        to_copy.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
        to_copy.dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
        to_copy.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
        to_copy.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
        info.attachmentCount = 1;
        info.pAttachments = &color;
        info.subpassCount = 1;
        info.pSubpasses = &subpass;
        info.dependencyCount = 1;
        info.pDependencies = &to_copy;
        if (auto e = check(fn.vkCreateRenderPass(device.device, &info, nullptr, &render_pass), "vkCreateRenderPass");
            !e.empty())
            return e;
        cleanup.push_back([this] { fn.vkDestroyRenderPass(device.device, render_pass, nullptr); });
        VkFramebufferCreateInfo framebuffer_info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        framebuffer_info.renderPass = render_pass;
        framebuffer_info.attachmentCount = 1;
        framebuffer_info.pAttachments = &fragment_output.view;
        framebuffer_info.width = width;
        framebuffer_info.height = height;
        framebuffer_info.layers = 1;
        if (auto e = check(fn.vkCreateFramebuffer(device.device, &framebuffer_info, nullptr, &framebuffer),
                           "vkCreateFramebuffer");
            !e.empty())
            return e;
        cleanup.push_back([this] { fn.vkDestroyFramebuffer(device.device, framebuffer, nullptr); });
        return {};
    }

    // The pipelines through kdop's helper, a pool for one copy of each one's sets, and the sets.
    std::string create_pipelines() {
        const auto kdop_check = [](VkResult result, const kdop::VariantPipeline& p, const char* what) {
            return result == VK_SUCCESS ? std::string()
                                        : std::string(what) + ": " + (p.failure ? p.failure : "failed") +
                                              " (VkResult " + std::to_string(result) + ")";
        };
        if (auto e =
                kdop_check(kdop::create_variant_pipeline(kdop_fn, device.device, *shaders.compute, compute_pipeline),
                           compute_pipeline, "kdop::create_variant_pipeline");
            !e.empty())
            return e;
        cleanup.push_back([this] { kdop::destroy_variant_pipeline(kdop_fn, device.device, compute_pipeline); });
        kdop::GraphicsTargets targets;
        targets.render_pass = render_pass;
        if (auto e = kdop_check(kdop::create_variant_graphics_pipeline(kdop_fn, device.device, *shaders.vertex,
                                                                       *shaders.fragment, targets, graphics_pipeline),
                                graphics_pipeline, "kdop::create_variant_graphics_pipeline");
            !e.empty())
            return e;
        cleanup.push_back([this] { kdop::destroy_variant_pipeline(kdop_fn, device.device, graphics_pipeline); });

        for (auto [pipeline, sets] :
             {std::pair{&compute_pipeline, compute_sets}, std::pair{&graphics_pipeline, graphics_sets}}) {
            VkDescriptorPool pool = VK_NULL_HANDLE;
            if (auto e = check(kdop::create_variant_descriptor_pool(kdop_fn, device.device, *pipeline, 1, pool),
                               "kdop::create_variant_descriptor_pool");
                !e.empty())
                return e;
            cleanup.push_back([this, pool] { kdop_fn.destroy_descriptor_pool(device.device, pool, nullptr); });
            if (auto e = check(kdop::allocate_variant_descriptor_sets(kdop_fn, device.device, pool, *pipeline, sets),
                               "kdop::allocate_variant_descriptor_sets");
                !e.empty())
                return e;
        }
        return {};
    }

    // The binding `name` of `entry`, which the shader must declare.
    static std::string binding(const kdop::Variant& entry, const char* name, const kdop::DescriptorBinding*& out) {
        out = kdop::find_binding(entry, name);
        return out ? std::string() : std::string(entry.name) + " declares no " + name;
    }

    // The same descriptors for a GLSL resolve and its HLSL port: where GLSL combines an image with
    // its sampler (sampler2D), HLSL declares a Texture2D and a SamplerState, found by name
    // (history_sampler beside history_frame, frame_samplers beside frames).
    std::string write_descriptors() {
        const kdop::Variant& compute = *shaders.compute;
        const kdop::Variant& fragment = *shaders.fragment;
        const kdop::DescriptorBinding *current_texture, *nearest_sampler, *history_frame, *resolved_frame, *parameters,
            *clip_distance, *frames, *fragment_parameters_binding;
        for (auto [entry, name, out] :
             {std::tuple{&compute, "current_texture", &current_texture},
              std::tuple{&compute, "nearest_sampler", &nearest_sampler},
              std::tuple{&compute, "history_frame", &history_frame},
              std::tuple{&compute, "resolved_frame", &resolved_frame}, std::tuple{&compute, "parameters", &parameters},
              std::tuple{&compute, "clip_distances", &clip_distance}, std::tuple{&fragment, "frames", &frames},
              std::tuple{&fragment, "parameters", &fragment_parameters_binding}})
            if (auto e = binding(*entry, name, *out); !e.empty()) return e;
        if (frames->count != 2) return "resolve_fragment's frames is not an array of 2";
        const kdop::DescriptorBinding* history_sampler = nullptr;
        if (history_frame->type == kdop::DescriptorType::sampled_image)
            if (auto e = binding(compute, "history_sampler", history_sampler); !e.empty()) return e;
        const kdop::DescriptorBinding* frame_samplers = nullptr;
        if (frames->type == kdop::DescriptorType::sampled_image) {
            if (auto e = binding(fragment, "frame_samplers", frame_samplers); !e.empty()) return e;
            if (frame_samplers->count != 2) return "resolve_fragment's frame_samplers is not an array of 2";
        }

        // A sampled image's write ignores the sampler and a combined one's takes it: one info serves both.
        const VkDescriptorImageInfo current_image{VK_NULL_HANDLE, current.view,
                                                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        const VkDescriptorImageInfo nearest_info{nearest, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED};
        const VkDescriptorImageInfo linear_info{linear, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED};
        const VkDescriptorImageInfo history_image{linear, history.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        const VkDescriptorImageInfo output_image{VK_NULL_HANDLE, compute_output.view, VK_IMAGE_LAYOUT_GENERAL};
        const VkDescriptorImageInfo both_frames[2] = {{nearest, current.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                                      history_image};
        const VkDescriptorImageInfo both_samplers[2] = {nearest_info, linear_info};
        const VkDescriptorBufferInfo compute_block{compute_parameters.buffer, 0, parameters->block_size};
        const VkDescriptorBufferInfo clip_block{clip_distances.buffer, 0, VK_WHOLE_SIZE};
        const VkDescriptorBufferInfo fragment_block{fragment_parameters.buffer, 0,
                                                    fragment_parameters_binding->block_size};

        // Each write's set, binding, type and count come from the reflection; only what it points at is ours.
        VkWriteDescriptorSet writes[10];
        std::uint32_t n = 0;
        auto image = [&](const kdop::DescriptorBinding* b, VkDescriptorSet* sets, const VkDescriptorImageInfo* info) {
            writes[n] = kdop::variant_descriptor_write(*b, sets[b->set]);
            writes[n++].pImageInfo = info;
        };
        auto buffer = [&](const kdop::DescriptorBinding* b, VkDescriptorSet* sets, const VkDescriptorBufferInfo* info) {
            writes[n] = kdop::variant_descriptor_write(*b, sets[b->set]);
            writes[n++].pBufferInfo = info;
        };
        image(current_texture, compute_sets, &current_image);
        image(nearest_sampler, compute_sets, &nearest_info);
        image(history_frame, compute_sets, &history_image);
        if (history_sampler) image(history_sampler, compute_sets, &linear_info);
        image(resolved_frame, compute_sets, &output_image);
        buffer(parameters, compute_sets, &compute_block);
        buffer(clip_distance, compute_sets, &clip_block);
        image(frames, graphics_sets, both_frames);
        if (frame_samplers) image(frame_samplers, graphics_sets, both_samplers);
        buffer(fragment_parameters_binding, graphics_sets, &fragment_block);
        fn.vkUpdateDescriptorSets(device.device, n, writes, 0, nullptr);
        return {};
    }

    std::string create() {
        if (auto e = load_functions(); !e.empty()) return e;

        // The shaders' own declarations size and type the resources: an engine's C++ structs must
        // match the reflected blocks, and the output image takes the format resolved_frame declares.
        const kdop::DescriptorBinding* block = kdop::find_binding(*shaders.compute, "parameters");
        if (!block || block->block_size != sizeof(ComputeParameters))
            return "resolve_compute's ResolveParameters is not the " + std::to_string(sizeof(ComputeParameters)) +
                   " bytes this file writes";
        block = kdop::find_binding(*shaders.fragment, "parameters");
        if (!block || block->block_size != sizeof(FragmentParameters))
            return "resolve_fragment's ResolveParameters is not the " + std::to_string(sizeof(FragmentParameters)) +
                   " bytes this file writes";
        const kdop::DescriptorBinding* output = kdop::find_binding(*shaders.compute, "resolved_frame");
        if (!output || output->format == 0) return "resolve_compute's resolved_frame declares no format";

        const VkBufferUsageFlags transfer = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        const VkImageUsageFlags input = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        const std::function<std::string()> steps[] = {
            [&] { return create_buffer(upload, 2 * image_bytes(), transfer); },
            [&] { return create_buffer(readback, 2 * image_bytes(), transfer); },
            [&] {
                return create_buffer(compute_parameters, sizeof(ComputeParameters), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
            },
            [&] {
                return create_buffer(fragment_parameters, sizeof(FragmentParameters),
                                     VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
            },
            [&] {
                return create_buffer(clip_distances, std::size_t(width) * height * sizeof(float),
                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
            },
            [&] { return create_texture(current, VK_FORMAT_R32G32B32A32_SFLOAT, input, width, height); },
            [&] { return create_texture(history, VK_FORMAT_R32G32B32A32_SFLOAT, input, width, height); },
            [&] {
                return create_texture(compute_output, static_cast<VkFormat>(output->format),
                                      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, width, height);
            },
            [&] {
                return create_texture(fragment_output, VK_FORMAT_R32G32B32A32_SFLOAT,
                                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, width,
                                      height);
            },
            [&] { return create_sampler(nearest, VK_FILTER_NEAREST); },
            [&] { return create_sampler(linear, VK_FILTER_LINEAR); },
            [&] { return create_render_pass(); },
            [&] { return create_pipelines(); },
            [&] { return write_descriptors(); },
        };
        for (const auto& step : steps)
            if (auto e = step(); !e.empty()) return e;

        return create_command_buffer();
    }

    // Upload, both resolves, read back: one submission.
    void record() {
        const VkPipelineStageFlags shaders_stage =
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
        const VkBufferImageCopy whole{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {width, height, 1}};
        VkBufferImageCopy second = whole;
        second.bufferOffset = image_bytes();
        for (VkImage image : {current.image, history.image})
            barrier(image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        fn.vkCmdCopyBufferToImage(commands, upload.buffer, current.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                                  &whole);
        fn.vkCmdCopyBufferToImage(commands, upload.buffer, history.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                                  &second);
        for (VkImage image : {current.image, history.image})
            barrier(image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    shaders_stage);
        barrier(compute_output.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 0, VK_ACCESS_SHADER_WRITE_BIT,
                VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);

        const kdop::Variant& compute = *shaders.compute;
        fn.vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, compute_pipeline.pipeline);
        fn.vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, compute_pipeline.pipeline_layout, 0,
                                   compute_pipeline.set_layout_count, compute_sets, 0, nullptr);
        fn.vkCmdDispatch(commands, (width + compute.local_size[0] - 1) / compute.local_size[0],
                         (height + compute.local_size[1] - 1) / compute.local_size[1], 1);

        VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        begin.renderPass = render_pass;
        begin.framebuffer = framebuffer;
        begin.renderArea = {{0, 0}, {width, height}};
        fn.vkCmdBeginRenderPass(commands, &begin, VK_SUBPASS_CONTENTS_INLINE);
        fn.vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, graphics_pipeline.pipeline);
        fn.vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, graphics_pipeline.pipeline_layout, 0,
                                   graphics_pipeline.set_layout_count, graphics_sets, 0, nullptr);
        const VkViewport viewport{0, 0, float(width), float(height), 0, 1};
        const VkRect2D scissor{{0, 0}, {width, height}};
        fn.vkCmdSetViewport(commands, 0, 1, &viewport);
        fn.vkCmdSetScissor(commands, 0, 1, &scissor);
        fn.vkCmdPushConstants(commands, graphics_pipeline.pipeline_layout, graphics_pipeline.push_constant_stages, 0,
                              graphics_pipeline.push_constant_size, &push_weight);
        fn.vkCmdDraw(commands, 3, 1, 0, 0);
        fn.vkCmdEndRenderPass(commands); // leaves fragment_output in TRANSFER_SRC_OPTIMAL

        barrier(compute_output.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_PIPELINE_STAGE_TRANSFER_BIT);
        fn.vkCmdCopyImageToBuffer(commands, compute_output.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer,
                                  1, &whole);
        fn.vkCmdCopyImageToBuffer(commands, fragment_output.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                  readback.buffer, 1, &second);
        // The copies and the clip-distance buffer's shader writes, made visible to the host.
        VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT;
        to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        fn.vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr, 0, nullptr);
    }

    float push_weight = 0; // the fragment resolve's push constant, Blend.current_weight
};

Resolver::Resolver(std::unique_ptr<State> state) : state_(std::move(state)) {}
Resolver::~Resolver() = default;

std::unique_ptr<Resolver> Resolver::create(const Device& device, const Shaders& shaders, std::uint32_t width,
                                           std::uint32_t height, std::string& error) {
    auto state = std::make_unique<State>();
    state->device = device;
    state->shaders = shaders;
    state->width = width;
    state->height = height;
    if (!device.get_instance_proc_addr || !shaders.compute || !shaders.vertex || !shaders.fragment || width == 0 ||
        height == 0)
        error = "engine::Resolver::create: a device, all three shaders and a non-empty size are needed";
    else
        error = state->create();
    if (!error.empty()) return nullptr;
    return std::unique_ptr<Resolver>(new Resolver(std::move(state)));
}

std::string Resolver::resolve(const Frames& frames, Resolved& out) {
    State& s = *state_;
    const std::size_t floats = s.image_bytes() / sizeof(float);
    if (frames.current.size() != floats || frames.history.size() != floats)
        return "engine::Resolver::resolve: frames of another size than the resolver's " + std::to_string(s.width) +
               "x" + std::to_string(s.height);
    std::memcpy(s.upload.mapped, frames.current.data(), s.image_bytes());
    std::memcpy(static_cast<char*>(s.upload.mapped) + s.image_bytes(), frames.history.data(), s.image_bytes());
    const ComputeParameters compute{{frames.motion[0], frames.motion[1]}, frames.current_weight};
    const FragmentParameters fragment{{frames.motion[0], frames.motion[1]}};
    std::memcpy(s.compute_parameters.mapped, &compute, sizeof compute);
    std::memcpy(s.fragment_parameters.mapped, &fragment, sizeof fragment);
    s.push_weight = frames.current_weight;

    if (auto e = s.run_once([&] { s.record(); }); !e.empty()) return e;

    const float* read = static_cast<const float*>(s.readback.mapped);
    out.compute.assign(read, read + floats);
    out.fragment.assign(read + floats, read + 2 * floats);
    const float* distances = static_cast<const float*>(s.clip_distances.mapped);
    out.clip_distance.assign(distances, distances + floats / 4);
    return {};
}

// The TAAU resolve, through kdop's run helper: it makes the pipeline, the textures and the
// storage image from the registry entry, keeps the history on the device and reads the output back.
struct Upscaler::State {
    std::unique_ptr<kdop::ResolveRunner> runner;
    std::uint32_t input_width = 0, input_height = 0;
    std::vector<float> motion; // RGBA: the motion in .xy
};

Upscaler::Upscaler(std::unique_ptr<State> state) : state_(std::move(state)) {}
Upscaler::~Upscaler() = default;

std::unique_ptr<Upscaler> Upscaler::create(const Device& device, const kdop::Variant& shader, std::uint32_t input_width,
                                           std::uint32_t input_height, std::uint32_t width, std::uint32_t height,
                                           std::string& error) {
    kdop::ResolveRunner::Layout layout;
    layout.inputs = {{"current_frame", input_width, input_height},
                     {"motion_frame", input_width, input_height},
                     {"history_frame", width, height}};
    layout.output = "resolved_frame";
    layout.width = width, layout.height = height;
    layout.history = "history_frame";
    auto state = std::make_unique<State>();
    state->runner = kdop::ResolveRunner::create(device, shader, layout, error);
    if (!state->runner) return nullptr;
    state->input_width = input_width, state->input_height = input_height;
    return std::unique_ptr<Upscaler>(new Upscaler(std::move(state)));
}

std::string Upscaler::resolve(const UpscaleFrames& frames, std::vector<float>& out) {
    State& s = *state_;
    const std::size_t pixels = std::size_t(s.input_width) * s.input_height;
    if (frames.motion.size() != 2 * pixels)
        return "engine::Upscaler::resolve: motion for other than the upscaler's " + std::to_string(s.input_width) +
               "x" + std::to_string(s.input_height) + " input";
    s.motion.assign(4 * pixels, 0.0f);
    for (std::size_t i = 0; i < pixels; ++i) {
        s.motion[4 * i] = frames.motion[2 * i];
        s.motion[4 * i + 1] = frames.motion[2 * i + 1];
    }
    for (std::string e : {s.runner->set_input("current_frame", frames.current.data(), frames.current.size()),
                          s.runner->set_input("motion_frame", s.motion.data(), s.motion.size()),
                          s.runner->set_push_constant("jitter", frames.jitter.data(), sizeof(float) * 2),
                          s.runner->set_push_constant("current_weight", &frames.current_weight, sizeof(float))})
        if (!e.empty()) return e;
    return s.runner->resolve(&out);
}

} // namespace engine
