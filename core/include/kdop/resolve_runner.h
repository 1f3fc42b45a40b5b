// Runs one compute resolve (a TAA or TAAU resolve with a kdop variant in it, or any compute shader
// of the registry) on the caller's Vulkan device, frame after frame: the textures it samples
// uploaded from RGBA floats, its push constants by member name, one dispatch over the output, the
// output copied on the device into the texture the next frame reads as its history, and read back
// when asked. What `kdop taa --resolve` does for a resolve, for an engine's own tests and tools,
// in tens of lines instead of two hundred of Vulkan:
//
//     kdop::ResolveRunner::Layout layout;
//     layout.inputs = {{"current_frame", in_w, in_h}, {"motion_frame", in_w, in_h}, {"history_frame", w, h}};
//     layout.output = "resolved_frame";
//     layout.width = w, layout.height = h;
//     layout.history = "history_frame"; // the output of each resolve becomes the next one's history
//     std::string error;
//     auto runner = kdop::ResolveRunner::create(device, *variants().find("upscale_compute"), layout, error);
//     for (each frame) {
//         runner->set_input("current_frame", color.data(), color.size());
//         runner->set_input("motion_frame", motion.data(), motion.size());
//         runner->set_push_constant("jitter", &jitter, sizeof jitter);
//         error = runner->resolve(&output); // empty on success
//     }
//
// Every texture is RGBA32F (a motion field's two floats in .xy) and sampled through a linear sampler
// clamped to the edge, combined or separate (a SamplerState binding gets it too); the output is a
// storage image of the format the shader declares; the history starts as zeros. Bindings are
// found by the names the shader declares, so a binding the layout does not name, or a
// push-constant member never set, is refused before the first dispatch rather than left undefined.
//
// C++17, header only, Vulkan 1.0; every call goes through vkGetInstanceProcAddr and
// vkGetDeviceProcAddr, so it works with volk and VK_NO_PROTOTYPES and links nothing. It is not
// kdop's own runtime (which needs kdop's libraries): it is what an engine compiles into its tools.
#pragma once

#include <kdop/variant.h>
#include <kdop/vulkan_pipeline.h>

#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace kdop {

// The caller's device; its queue must do compute.
struct RunnerDevice {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    std::uint32_t queue_family = 0;
    PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
};

// clang-format off
#define KDOP_RUNNER_FUNCTIONS(X) \
    X(vkCreateBuffer) X(vkDestroyBuffer) X(vkGetBufferMemoryRequirements) X(vkBindBufferMemory) \
    X(vkAllocateMemory) X(vkFreeMemory) X(vkMapMemory) \
    X(vkCreateImage) X(vkDestroyImage) X(vkGetImageMemoryRequirements) X(vkBindImageMemory) \
    X(vkCreateImageView) X(vkDestroyImageView) X(vkCreateSampler) X(vkDestroySampler) \
    X(vkCreateCommandPool) X(vkDestroyCommandPool) X(vkAllocateCommandBuffers) X(vkResetCommandBuffer) \
    X(vkBeginCommandBuffer) X(vkEndCommandBuffer) X(vkCmdPipelineBarrier) X(vkCmdClearColorImage) \
    X(vkCmdCopyBufferToImage) X(vkCmdCopyImageToBuffer) X(vkCmdCopyImage) X(vkCmdBindPipeline) \
    X(vkCmdBindDescriptorSets) X(vkCmdPushConstants) X(vkCmdDispatch) X(vkUpdateDescriptorSets) \
    X(vkQueueSubmit) X(vkQueueWaitIdle) X(vkDeviceWaitIdle)
// clang-format on

class ResolveRunner {
public:
    struct Input {
        const char* name;            // a sampled texture of the shader (sampler2D, texture2D, Texture2D)
        std::uint32_t width, height; // in texels
    };
    // Names are read by create() only.
    struct Layout {
        std::vector<Input> inputs;    // every texture the shader samples, the history included
        const char* output = nullptr; // its storage image, written over width x height
        std::uint32_t width = 0, height = 0;
        const char* history = nullptr; // an input of the output's size that each resolve's output is
                                       // copied into, on the device; nullptr: none
    };

    // The pipeline and resources; nullptr with `error` saying what failed or what does not match.
    static std::unique_ptr<ResolveRunner> create(const RunnerDevice& device, const Variant& shader,
                                                 const Layout& layout, std::string& error) {
        std::unique_ptr<ResolveRunner> r(new ResolveRunner(device, shader, layout));
        error = r->create();
        if (!error.empty()) return nullptr;
        return r;
    }
    ~ResolveRunner() {
        if (device_.device && fn_.vkDeviceWaitIdle) fn_.vkDeviceWaitIdle(device_.device);
        for (auto it = cleanup_.rbegin(); it != cleanup_.rend(); ++it) (*it)();
    }
    ResolveRunner(const ResolveRunner&) = delete;
    ResolveRunner& operator=(const ResolveRunner&) = delete;

    // Input `name`'s texels, RGBA floats row-major from the top-left (width x height x 4 of them),
    // uploaded by the next resolve(). The history need not be set: it is the last output.
    std::string set_input(const char* name, const float* rgba, std::size_t floats) {
        Texture* t = texture(name);
        if (!t) return fail(std::string("has no input '") + name + "'");
        if (floats != std::size_t(t->width) * t->height * 4)
            return fail(std::string("input '") + name + "' takes " + std::to_string(t->width) + "x" +
                        std::to_string(t->height) + " RGBA texels, not " + std::to_string(floats) + " floats");
        std::memcpy(static_cast<char*>(upload_.mapped) + t->offset, rgba, floats * sizeof(float));
        t->pending = true;
        return {};
    }

    // The push-constant member `name`'s bytes: a float, a uint, a vec2..., its reflected size.
    std::string set_push_constant(const char* name, const void* bytes, std::size_t size) {
        for (std::uint32_t i = 0; i < shader_.push_constant_count; ++i) {
            const PushConstantMember& m = shader_.push_constants[i];
            if (std::strcmp(m.name, name) != 0) continue;
            if (size != m.size)
                return fail(std::string("push constant '") + name + "' is " + std::to_string(m.size) + " bytes, not " +
                            std::to_string(size));
            std::memcpy(push_.data() + m.offset, bytes, size);
            push_set_[i] = true;
            return {};
        }
        return fail(std::string("has no push constant '") + name + "'");
    }

    // One resolve: the inputs set since the last one uploaded, the dispatch, the output copied into
    // the history; with `out`, the output read back as RGBA floats. Empty on success.
    std::string resolve(std::vector<float>* out = nullptr) {
        for (std::uint32_t i = 0; i < shader_.push_constant_count; ++i)
            if (!push_set_[i])
                return fail(std::string("push constant '") + shader_.push_constants[i].name + "' was never set");
        for (const Texture& t : inputs_)
            if (!t.pending && !t.filled) return fail(std::string("input '") + t.name + "' was never set");
        auto error = run([&] { record(out != nullptr); });
        if (!error.empty()) return error;
        for (Texture& t : inputs_) t.filled = true, t.pending = false;
        if (out) {
            const float* read = static_cast<const float*>(readback_.mapped);
            out->assign(read, read + std::size_t(layout_.width) * layout_.height * 4);
        }
        return {};
    }

private:
    struct Functions {
#define KDOP_RUNNER_DECLARE(name) PFN_##name name = nullptr;
        KDOP_RUNNER_FUNCTIONS(KDOP_RUNNER_DECLARE)
#undef KDOP_RUNNER_DECLARE
    };
    struct Buffer {
        VkBuffer buffer = VK_NULL_HANDLE;
        void* mapped = nullptr; // host-visible and coherent, mapped for the runner's life
    };
    struct Texture {
        std::string name;
        std::uint32_t width = 0, height = 0;
        VkImage image = VK_NULL_HANDLE;
        VkImageView view = VK_NULL_HANDLE;
        VkDeviceSize offset = 0; // in the upload buffer
        bool pending = false;    // set since the last resolve
        bool filled = false;     // holds what a set or a copy put there
        const DescriptorBinding* binding = nullptr;
    };

    ResolveRunner(const RunnerDevice& device, const Variant& shader, const Layout& layout)
        : device_(device), shader_(shader), layout_(layout) {}

    std::string fail(const std::string& what) const {
        return std::string("kdop::ResolveRunner: ") + shader_.name + ": " + what;
    }
    std::string check(VkResult result, const char* what) const {
        return result == VK_SUCCESS ? std::string()
                                    : fail(std::string(what) + " failed: VkResult " + std::to_string(result));
    }
    Texture* texture(const char* name) {
        for (Texture& t : inputs_)
            if (t.name == name) return &t;
        return nullptr;
    }

    std::string create() {
        if (!device_.get_instance_proc_addr || !device_.device) return fail("no device");
        if (shader_.stage != ShaderStage::compute) return fail("not a compute shader");
        if (layout_.width == 0 || layout_.height == 0 || !layout_.output) return fail("no output, or an empty one");
        const auto get_device_proc_addr = reinterpret_cast<PFN_vkGetDeviceProcAddr>(
            device_.get_instance_proc_addr(device_.instance, "vkGetDeviceProcAddr"));
        const auto get_memory_properties = reinterpret_cast<PFN_vkGetPhysicalDeviceMemoryProperties>(
            device_.get_instance_proc_addr(device_.instance, "vkGetPhysicalDeviceMemoryProperties"));
        if (!get_device_proc_addr || !get_memory_properties) return fail("the instance lacks a Vulkan 1.0 entry point");
        if (load_variant_functions(device_.device, get_device_proc_addr, kdop_fn_) != VK_SUCCESS)
            return fail("the device lacks an entry point");
#define KDOP_RUNNER_LOAD(name)                                                                                         \
    fn_.name = reinterpret_cast<PFN_##name>(get_device_proc_addr(device_.device, #name));                              \
    if (!fn_.name) return fail("the device lacks " #name);
        KDOP_RUNNER_FUNCTIONS(KDOP_RUNNER_LOAD)
#undef KDOP_RUNNER_LOAD
        get_memory_properties(device_.physical_device, &memory_);

        // Every binding of the shader is one the layout names: an input, the output or a sampler.
        output_binding_ = find_binding(shader_, layout_.output);
        if (!output_binding_ || output_binding_->type != DescriptorType::storage_image || output_binding_->format == 0)
            return fail(std::string("has no storage image '") + layout_.output + "' of a declared format");
        VkDeviceSize offset = 0;
        for (const Input& in : layout_.inputs) {
            Texture t;
            t.name = in.name;
            t.width = in.width, t.height = in.height;
            t.offset = offset;
            t.binding = find_binding(shader_, in.name);
            if (!t.binding || (t.binding->type != DescriptorType::combined_image_sampler &&
                               t.binding->type != DescriptorType::sampled_image))
                return fail(std::string("has no sampled texture '") + in.name + "'");
            if (t.width == 0 || t.height == 0) return fail(std::string("input '") + in.name + "' is empty");
            offset += VkDeviceSize(t.width) * t.height * 16;
            inputs_.push_back(t);
        }
        for (std::uint32_t i = 0; i < shader_.binding_count; ++i) {
            const DescriptorBinding& b = shader_.bindings[i];
            if (&b != output_binding_ && b.type != DescriptorType::sampler && !texture(b.name))
                return fail(std::string("its binding '") + b.name + "' is not in the layout's inputs or output");
        }
        history_ = layout_.history ? texture(layout_.history) : nullptr;
        const Texture* history = history_;
        if (layout_.history && (!history || history->width != layout_.width || history->height != layout_.height ||
                                output_binding_->format != VK_FORMAT_R32G32B32A32_SFLOAT))
            return fail(std::string("the history '") + layout_.history +
                        "' is not an input of the output's size, or the output is not rgba32f to copy into it");
        push_.assign(shader_.push_constant_size, 0);
        push_set_.assign(shader_.push_constant_count, false);

        const VkDeviceSize output_bytes = VkDeviceSize(layout_.width) * layout_.height * 16;
        const VkImageUsageFlags sampled = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        if (auto e = create_buffer(upload_, offset > 0 ? offset : 16, VK_BUFFER_USAGE_TRANSFER_SRC_BIT); !e.empty())
            return e;
        if (auto e = create_buffer(readback_, output_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT); !e.empty()) return e;
        for (Texture& t : inputs_)
            if (auto e = create_texture(t, VK_FORMAT_R32G32B32A32_SFLOAT, sampled, t.width, t.height); !e.empty())
                return e;
        output_.width = layout_.width, output_.height = layout_.height;
        if (auto e = create_texture(output_, static_cast<VkFormat>(output_binding_->format),
                                    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, layout_.width,
                                    layout_.height);
            !e.empty())
            return e;
        if (auto e = create_sampler(); !e.empty()) return e;
        if (create_variant_pipeline(kdop_fn_, device_.device, shader_, pipeline_) != VK_SUCCESS)
            return fail(std::string("kdop::create_variant_pipeline: ") +
                        (pipeline_.failure ? pipeline_.failure : "failed"));
        cleanup_.push_back([this] { destroy_variant_pipeline(kdop_fn_, device_.device, pipeline_); });
        VkDescriptorPool pool = VK_NULL_HANDLE;
        if (auto e = check(create_variant_descriptor_pool(kdop_fn_, device_.device, pipeline_, 1, pool),
                           "vkCreateDescriptorPool");
            !e.empty())
            return e;
        if (pool) cleanup_.push_back([this, pool] { kdop_fn_.destroy_descriptor_pool(device_.device, pool, nullptr); });
        if (pool)
            if (auto e = check(allocate_variant_descriptor_sets(kdop_fn_, device_.device, pool, pipeline_, sets_),
                               "vkAllocateDescriptorSets");
                !e.empty())
                return e;
        write_descriptors();
        if (auto e = create_commands(); !e.empty()) return e;
        // The history and every input start as zeros: a first frame's blend weighs its history by 0,
        // and 0 x NaN is NaN.
        if (auto e = run([&] {
                for (Texture& t : inputs_) clear(t);
            });
            !e.empty())
            return e;
        if (history_) history_->filled = true;
        return {};
    }

    void write_descriptors() {
        std::vector<VkDescriptorImageInfo> infos(shader_.binding_count);
        std::vector<VkWriteDescriptorSet> writes;
        for (std::uint32_t i = 0; i < shader_.binding_count; ++i) {
            const DescriptorBinding& b = shader_.bindings[i];
            if (b.count != 1) continue; // arrays of textures are not a resolve's; refused above by name
            const Texture* t = &b == output_binding_ ? &output_ : texture(b.name);
            infos[i] = {sampler_, t ? t->view : VK_NULL_HANDLE,
                        &b == output_binding_ ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            if (b.type == DescriptorType::sampled_image || b.type == DescriptorType::storage_image)
                infos[i].sampler = VK_NULL_HANDLE;
            VkWriteDescriptorSet w = variant_descriptor_write(b, sets_[b.set]);
            w.pImageInfo = &infos[i];
            writes.push_back(w);
        }
        fn_.vkUpdateDescriptorSets(device_.device, std::uint32_t(writes.size()), writes.data(), 0, nullptr);
    }

    std::string allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags flags, VkDeviceMemory& out) {
        std::uint32_t type = 0;
        while (type < memory_.memoryTypeCount && !((requirements.memoryTypeBits >> type & 1u) &&
                                                   (memory_.memoryTypes[type].propertyFlags & flags) == flags))
            ++type;
        if (type == memory_.memoryTypeCount) return fail("no memory type for a resource");
        VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        info.allocationSize = requirements.size;
        info.memoryTypeIndex = type;
        if (auto e = check(fn_.vkAllocateMemory(device_.device, &info, nullptr, &out), "vkAllocateMemory"); !e.empty())
            return e;
        cleanup_.push_back([this, out] { fn_.vkFreeMemory(device_.device, out, nullptr); });
        return {};
    }

    std::string create_buffer(Buffer& b, VkDeviceSize size, VkBufferUsageFlags usage) {
        VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        info.size = size;
        info.usage = usage;
        if (auto e = check(fn_.vkCreateBuffer(device_.device, &info, nullptr, &b.buffer), "vkCreateBuffer"); !e.empty())
            return e;
        cleanup_.push_back([this, buffer = b.buffer] { fn_.vkDestroyBuffer(device_.device, buffer, nullptr); });
        VkMemoryRequirements requirements;
        fn_.vkGetBufferMemoryRequirements(device_.device, b.buffer, &requirements);
        VkDeviceMemory memory = VK_NULL_HANDLE;
        if (auto e = allocate(requirements, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                              memory);
            !e.empty())
            return e;
        if (auto e = check(fn_.vkBindBufferMemory(device_.device, b.buffer, memory, 0), "vkBindBufferMemory");
            !e.empty())
            return e;
        return check(fn_.vkMapMemory(device_.device, memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
    }

    std::string create_texture(Texture& t, VkFormat format, VkImageUsageFlags usage, std::uint32_t width,
                               std::uint32_t height) {
        VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        info.imageType = VK_IMAGE_TYPE_2D;
        info.format = format;
        info.extent = {width, height, 1};
        info.mipLevels = info.arrayLayers = 1;
        info.samples = VK_SAMPLE_COUNT_1_BIT;
        info.tiling = VK_IMAGE_TILING_OPTIMAL;
        info.usage = usage;
        info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        if (auto e = check(fn_.vkCreateImage(device_.device, &info, nullptr, &t.image), "vkCreateImage"); !e.empty())
            return e;
        cleanup_.push_back([this, image = t.image] { fn_.vkDestroyImage(device_.device, image, nullptr); });
        VkMemoryRequirements requirements;
        fn_.vkGetImageMemoryRequirements(device_.device, t.image, &requirements);
        VkDeviceMemory memory = VK_NULL_HANDLE;
        if (auto e = allocate(requirements, 0, memory); !e.empty()) return e;
        if (auto e = check(fn_.vkBindImageMemory(device_.device, t.image, memory, 0), "vkBindImageMemory"); !e.empty())
            return e;
        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view.image = t.image;
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = format;
        view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        if (auto e = check(fn_.vkCreateImageView(device_.device, &view, nullptr, &t.view), "vkCreateImageView");
            !e.empty())
            return e;
        cleanup_.push_back([this, v = t.view] { fn_.vkDestroyImageView(device_.device, v, nullptr); });
        return {};
    }

    std::string create_sampler() {
        VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        info.magFilter = info.minFilter = VK_FILTER_LINEAR;
        info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
        info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        if (auto e = check(fn_.vkCreateSampler(device_.device, &info, nullptr, &sampler_), "vkCreateSampler");
            !e.empty())
            return e;
        cleanup_.push_back([this] { fn_.vkDestroySampler(device_.device, sampler_, nullptr); });
        return {};
    }

    std::string create_commands() {
        VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool_info.queueFamilyIndex = device_.queue_family;
        VkCommandPool pool = VK_NULL_HANDLE;
        if (auto e = check(fn_.vkCreateCommandPool(device_.device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
            !e.empty())
            return e;
        cleanup_.push_back([this, pool] { fn_.vkDestroyCommandPool(device_.device, pool, nullptr); });
        VkCommandBufferAllocateInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        info.commandPool = pool;
        info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        info.commandBufferCount = 1;
        return check(fn_.vkAllocateCommandBuffers(device_.device, &info, &commands_), "vkAllocateCommandBuffers");
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
        fn_.vkCmdPipelineBarrier(commands_, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
    }

    // Into the transfer destination layout and back to where dispatches sample it, around `write`.
    template <class Write>
    void transfer_into(const Texture& t, Write write) {
        barrier(t.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        write();
        barrier(t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
    }

    void clear(const Texture& t) {
        transfer_into(t, [&] {
            const VkClearColorValue zero{};
            const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            fn_.vkCmdClearColorImage(commands_, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &all);
        });
    }

    // The uploads, the dispatch, the copy into the history and, with `read`, the read-back.
    void record(bool read) {
        for (const Texture& t : inputs_)
            if (t.pending)
                transfer_into(t, [&] {
                    const VkBufferImageCopy copy{
                        t.offset, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {t.width, t.height, 1}};
                    fn_.vkCmdCopyBufferToImage(commands_, upload_.buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                               1, &copy);
                });
        barrier(output_.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 0, VK_ACCESS_SHADER_WRITE_BIT,
                VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
        fn_.vkCmdBindPipeline(commands_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.pipeline);
        if (pipeline_.set_layout_count)
            fn_.vkCmdBindDescriptorSets(commands_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.pipeline_layout, 0,
                                        pipeline_.set_layout_count, sets_, 0, nullptr);
        if (!push_.empty())
            fn_.vkCmdPushConstants(commands_, pipeline_.pipeline_layout, pipeline_.push_constant_stages, 0,
                                   std::uint32_t(push_.size()), push_.data());
        fn_.vkCmdDispatch(commands_, (layout_.width + shader_.local_size[0] - 1) / shader_.local_size[0],
                          (layout_.height + shader_.local_size[1] - 1) / shader_.local_size[1], 1);
        barrier(output_.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_PIPELINE_STAGE_TRANSFER_BIT);
        const VkExtent3D extent{layout_.width, layout_.height, 1};
        if (const Texture* history = history_)
            transfer_into(*history, [&] {
                VkImageCopy copy{};
                copy.srcSubresource = copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                copy.extent = extent;
                fn_.vkCmdCopyImage(commands_, output_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, history->image,
                                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
            });
        if (!read) return;
        const VkBufferImageCopy whole{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, extent};
        fn_.vkCmdCopyImageToBuffer(commands_, output_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer, 1,
                                   &whole);
        VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        fn_.vkCmdPipelineBarrier(commands_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host,
                                 0, nullptr, 0, nullptr);
    }

    // Records the command buffer afresh with `record_commands`, submits it and waits.
    template <class Record>
    std::string run(Record record_commands) {
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        if (auto e = check(fn_.vkResetCommandBuffer(commands_, 0), "vkResetCommandBuffer"); !e.empty()) return e;
        if (auto e = check(fn_.vkBeginCommandBuffer(commands_, &begin), "vkBeginCommandBuffer"); !e.empty()) return e;
        record_commands();
        if (auto e = check(fn_.vkEndCommandBuffer(commands_), "vkEndCommandBuffer"); !e.empty()) return e;
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &commands_;
        if (auto e = check(fn_.vkQueueSubmit(device_.queue, 1, &submit, VK_NULL_HANDLE), "vkQueueSubmit"); !e.empty())
            return e;
        return check(fn_.vkQueueWaitIdle(device_.queue), "vkQueueWaitIdle");
    }

    RunnerDevice device_;
    const Variant& shader_;
    Layout layout_;
    Functions fn_;
    VariantVulkanFunctions kdop_fn_;
    VkPhysicalDeviceMemoryProperties memory_{};
    std::vector<std::function<void()>> cleanup_; // newest last, run in reverse by the destructor
    std::vector<Texture> inputs_;                // not resized after create(): history_ points into it
    Texture* history_ = nullptr;                 // layout.history's, or none
    Texture output_;
    const DescriptorBinding* output_binding_ = nullptr;
    Buffer upload_, readback_;
    VkSampler sampler_ = VK_NULL_HANDLE;
    VariantPipeline pipeline_;
    VkDescriptorSet sets_[kMaxVariantDescriptorSets] = {};
    VkCommandBuffer commands_ = VK_NULL_HANDLE;
    std::vector<unsigned char> push_;
    std::vector<bool> push_set_;
};

#undef KDOP_RUNNER_FUNCTIONS

} // namespace kdop
