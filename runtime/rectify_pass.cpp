#include "runtime/rectify_pass.h"

#include "runtime/device_image.h"
#include "runtime/vulkan_error.h"

#include <fmt/format.h>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

namespace kdop {
namespace {

constexpr VkFormat kOutputFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kHalfOutputFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

VkBufferImageCopy whole_image(uint32_t w, uint32_t h, VkDeviceSize offset) {
    VkBufferImageCopy copy{};
    copy.bufferOffset = offset;
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {w, h, 1};
    return copy;
}

} // namespace

Result<void> RectifyPass::allocate(const VkMemoryRequirements& req, VkMemoryPropertyFlags flags,
                                   VkDeviceMemory& memory) {
    auto type = context_.memory_type(req.memoryTypeBits, flags);
    if (!type) return std::unexpected(type.error());
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = *type;
    KDOP_VK_TRY(vkAllocateMemory(context_.device(), &alloc, nullptr, &memory));
    return {};
}

Result<void> RectifyPass::create_texture(Texture& t, VkFormat format, VkImageUsageFlags usage, uint32_t width,
                                         uint32_t height) {
    VkDevice device = context_.device();
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    KDOP_VK_TRY(vkCreateImage(device, &info, nullptr, &t.image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, t.image, &req);
    if (auto ok = allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, t.memory); !ok) return ok;
    KDOP_VK_TRY(vkBindImageMemory(device, t.image, t.memory, 0));
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = t.image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    KDOP_VK_TRY(vkCreateImageView(device, &view, nullptr, &t.view));
    return {};
}

Result<std::unique_ptr<RectifyPass>> RectifyPass::create(const Context& context, uint32_t width, uint32_t height,
                                                         TextureFormat format) {
    return create(context, width, height, format, std::vector<std::string>{"current_frame", "history_frame"});
}

Result<std::unique_ptr<RectifyPass>> RectifyPass::create(const Context& context, uint32_t width, uint32_t height,
                                                         TextureFormat format, std::vector<std::string> inputs) {
    std::vector<PassInput> four;
    for (std::string& name : inputs) four.push_back({std::move(name), 4});
    return create(context, width, height, format, std::move(four));
}

Result<std::unique_ptr<RectifyPass>> RectifyPass::create(const Context& context, uint32_t width, uint32_t height,
                                                         TextureFormat format, std::vector<PassInput> inputs) {
    if (inputs.empty()) return fail("a rectify pass needs at least one input");
    if (width == 0 || height == 0) return fail(fmt::format("cannot rectify an empty {}x{} image", width, height));
    // Checked here rather than left to vkCreateImage, which is undefined (and a validation error)
    // beyond the limit.
    const uint32_t limit = context.properties().limits.maxImageDimension2D;
    for (PassInput& in : inputs) {
        if (in.width == 0 && in.height == 0) in.width = width, in.height = height;
        if (in.width == 0 || in.height == 0)
            return fail(fmt::format("input '{}': cannot rectify an empty {}x{} image", in.name, in.width, in.height));
    }
    auto too_large = [&](uint32_t w, uint32_t h) -> Result<void> {
        if (w <= limit && h <= limit) return {};
        return fail(fmt::format("a {}x{} image is larger than {} allows: at most {} pixels on a side", w, h,
                                context.device_name(), limit));
    };
    if (auto ok = too_large(width, height); !ok) return std::unexpected(ok.error());
    for (const PassInput& in : inputs)
        if (auto ok = too_large(in.width, in.height); !ok) return std::unexpected(ok.error());
    std::unique_ptr<RectifyPass> p(new RectifyPass(context));
    p->width_ = width;
    p->height_ = height;
    p->format_ = format;
    VkDevice device = context.device();
    const VkDeviceSize pixels = VkDeviceSize(width) * height;

    const VkImageUsageFlags input_usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    VkDeviceSize upload_bytes = 0;
    for (PassInput& in : inputs) {
        if (in.channels != 1 && in.channels != 2 && in.channels != 4)
            return fail(
                fmt::format("input '{}' of {} channels: a rectify pass's have 1, 2 or 4", in.name, in.channels));
        if (in.channels != 4 && format == TextureFormat::rgba16f)
            return fail(
                fmt::format("input '{}' of {} channels: an rgba16f pass's inputs have 4", in.name, in.channels));
        p->inputs_.push_back({std::move(in.name), in.channels, in.width, in.height, std::vector<Texture>(1)});
        if (auto ok = p->create_texture(p->inputs_.back().slots[0], vk_format(format, in.channels), input_usage,
                                        in.width, in.height);
            !ok)
            return std::unexpected(ok.error());
        upload_bytes += VkDeviceSize(in.width) * in.height * texel_bytes(format, in.channels);
    }
    const auto input_count = static_cast<uint32_t>(p->inputs_.size());
    if (auto ok = p->create_texture(p->output_, kOutputFormat,
                                    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, width, height);
        !ok)
        return std::unexpected(ok.error());
    auto upload = DeviceBuffer::create(context, upload_bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                       DeviceBuffer::Memory::host, "the inputs' upload");
    if (!upload) return std::unexpected(upload.error());
    p->upload_ = std::move(*upload);
    auto readback = DeviceBuffer::create(context, pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                         DeviceBuffer::Memory::host, "the output's read-back");
    if (!readback) return std::unexpected(readback.error());
    p->readback_ = std::move(*readback);

    // texelFetch ignores filtering and addressing; a combined image sampler still needs a sampler.
    VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sampler.magFilter = sampler.minFilter = VK_FILTER_NEAREST;
    sampler.addressModeU = sampler.addressModeV = sampler.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    KDOP_VK_TRY(vkCreateSampler(device, &sampler, nullptr, &p->sampler_));
    sampler.magFilter = sampler.minFilter = VK_FILTER_LINEAR;
    KDOP_VK_TRY(vkCreateSampler(device, &sampler, nullptr, &p->linear_sampler_));

    // A renderer's resolve may read its inputs as separate textures, with one sampler or several.
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, input_count},
                                          {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, input_count},
                                          {VK_DESCRIPTOR_TYPE_SAMPLER, input_count},
                                          {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, input_count},
                                          {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
    auto sets = KernelSets::create(context, sizes, 1);
    if (!sets) return std::unexpected(sets.error());
    p->kernel_sets_ = std::move(*sets);

    auto commands = OneShotCommands::create(context);
    if (!commands) return std::unexpected(commands.error());
    p->commands_ = std::move(*commands);

    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(context.physical_device(), &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(context.physical_device(), &family_count, families.data());
    if (families[context.queue_family()].timestampValidBits > 0) {
        VkQueryPoolCreateInfo query{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        query.queryType = VK_QUERY_TYPE_TIMESTAMP;
        query.queryCount = 2;
        KDOP_VK_TRY(vkCreateQueryPool(device, &query, nullptr, &p->timestamps_));
    }
    return p;
}

Result<void> RectifyPass::upload(const Image& current, const Image& history) {
    if (inputs_.size() != 2) return fail("upload(current, history) on a pass of other inputs");
    const Image* images[] = {&current, &history};
    return upload(images);
}

Result<void> RectifyPass::upload(std::span<const Image* const> images) {
    if (images.size() != inputs_.size())
        return fail(fmt::format("{} images for a pass of {} inputs", images.size(), inputs_.size()));
    for (std::size_t i = 0; i < images.size(); ++i)
        if (const Image* image = images[i];
            image && (image->width != inputs_[i].width || image->height != inputs_[i].height))
            return fail(fmt::format("image is {}x{}, the pass's input '{}' is {}x{}", image->width, image->height,
                                    inputs_[i].name, inputs_[i].width, inputs_[i].height));
    const std::vector<VkDeviceSize> offsets = upload_offsets();
    auto* bytes = static_cast<std::byte*>(upload_.mapped());
    std::vector<bool> which(images.size());
    for (std::size_t i = 0; i < images.size(); ++i)
        if (images[i]) {
            pack(*images[i], format_, inputs_[i].channels, bytes + offsets[i]);
            which[i] = true;
        }
    return copy_uploads(which);
}

Result<void> RectifyPass::upload(std::string_view name, std::span<const float> texels) {
    auto in = input(name);
    if (!in) return std::unexpected(in.error());
    const std::size_t floats = std::size_t((*in)->width) * (*in)->height * (*in)->channels;
    if (format_ != TextureFormat::rgba32f || texels.size() != floats)
        return fail(fmt::format("'{}': {} floats for a {} input of {}x{} pixels of {} channels", name, texels.size(),
                                to_string(format_), (*in)->width, (*in)->height, (*in)->channels));
    const std::size_t i = std::size_t(*in - inputs_.data());
    std::memcpy(static_cast<std::byte*>(upload_.mapped()) + upload_offsets()[i], texels.data(), floats * 4);
    std::vector<bool> which(inputs_.size());
    which[i] = true;
    return copy_uploads(which);
}

std::vector<VkDeviceSize> RectifyPass::upload_offsets() const {
    std::vector<VkDeviceSize> offsets(inputs_.size());
    for (std::size_t i = 1; i < inputs_.size(); ++i) {
        const Input& before = inputs_[i - 1];
        offsets[i] =
            offsets[i - 1] + VkDeviceSize(before.width) * before.height * texel_bytes(format_, before.channels);
    }
    return offsets;
}

Result<void> RectifyPass::copy_uploads(const std::vector<bool>& which) {
    const std::vector<VkDeviceSize> offsets = upload_offsets();
    auto copied = commands_->run([&](VkCommandBuffer cb) {
        for (std::size_t i = 0; i < which.size(); ++i) {
            if (!which[i]) continue;
            const Texture& t = inputs_[i].texture();
            image_barrier(cb, t.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                          VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT);
            VkBufferImageCopy copy = whole_image(inputs_[i].width, inputs_[i].height, offsets[i]);
            vkCmdCopyBufferToImage(cb, upload_.buffer(), t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
            image_barrier(cb, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                          VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
        }
    });
    if (!copied) return std::unexpected(copied.error());
    for (std::size_t i = 0; i < which.size(); ++i)
        if (which[i]) inputs_[i].uploaded = true;
    return {};
}

Result<DispatchTiming> RectifyPass::dispatch(const Kernel& kernel, float gamma) {
    const PushConstantValue push[] = {{"gamma", {gamma}}};
    // Clip kernels take gamma or nothing; pass gamma only to those that have it.
    const bool takes_gamma = !kernel.push_constants().empty();
    return dispatch(kernel, takes_gamma ? std::span(push) : std::span<const PushConstantValue>{});
}

Result<DispatchTiming> RectifyPass::dispatch(const Kernel& kernel, std::span<const PushConstantValue> values) {
    return dispatch(kernel, values, {});
}

Result<DispatchTiming> RectifyPass::dispatch(const Kernel& kernel, std::span<const PushConstantValue> values,
                                             std::span<const BindingAs> as, std::span<const UniformBlock> uniforms) {
    VkDevice device = context_.device();

    if (auto ok = kernel_sets_.reset(); !ok) return std::unexpected(ok.error());
    auto allocated = kernel_sets_.allocate(kernel);
    if (!allocated) return std::unexpected(allocated.error());
    const VkDescriptorSet set = *allocated;
    // Each binding the registry reports gets the image its name asks for (the names of the
    // compute-shader template, shader_templates/rectify.comp.in, or those given to create(), or
    // what `as` gives it), whatever its binding number.
    const VkSampler sampler = as.empty() ? sampler_ : linear_sampler_;
    // A renderer's resolve may keep its history in half floats: its output is then written there.
    bool half = false;
    for (const Kernel::Binding& b : kernel.bindings())
        if (b.type == DescriptorType::storage_image && b.format == kHalfOutputFormat) half = true;
    if (half && !half_output_.image)
        if (auto ok = create_texture(half_output_, kHalfOutputFormat,
                                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, width_, height_);
            !ok)
            return std::unexpected(ok.error());
    const Texture& output = half ? half_output_ : output_;
    std::vector<Bound> bound;
    for (const Kernel::Binding& b : kernel.bindings()) {
        const auto given = std::find_if(as.begin(), as.end(), [&](const BindingAs& a) { return a.binding == b.name; });
        const std::string_view wanted = given != as.end() ? given->input : std::string_view(b.name);
        if (wanted == kSampler && b.type == DescriptorType::sampler) {
            bound.push_back({b.binding, BoundImage{VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED, sampler}});
            continue;
        }
        const auto block =
            std::find_if(uniforms.begin(), uniforms.end(), [&](const UniformBlock& u) { return u.binding == b.name; });
        if (block != uniforms.end() && b.type == DescriptorType::uniform_buffer) {
            auto buffer = uniform_buffers_.find(b.name);
            if (buffer == uniform_buffers_.end() || buffer->second.size() < block->bytes.size()) {
                auto made = DeviceBuffer::create(context_, block->bytes.size(), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                                 DeviceBuffer::Memory::host, "a uniform block");
                if (!made) return std::unexpected(made.error());
                buffer = uniform_buffers_.insert_or_assign(b.name, std::move(*made)).first;
            }
            std::memcpy(buffer->second.mapped(), block->bytes.data(), block->bytes.size());
            bound.push_back({b.binding, BoundBuffer{buffer->second.buffer()}});
            continue;
        }
        const auto input =
            std::find_if(inputs_.begin(), inputs_.end(), [&](const Input& in) { return in.name == wanted; });
        const Texture* texture = wanted == kOutput ? &output : input != inputs_.end() ? &input->texture() : nullptr;
        const bool storage = b.type == DescriptorType::storage_image;
        const bool separate = b.type == DescriptorType::sampled_image;
        const bool image = storage || separate || b.type == DescriptorType::combined_image_sampler;
        if (!texture || !image || storage != (texture == &output)) {
            std::string provided;
            for (const Input& in : inputs_) provided += in.name + " ";
            return fail(fmt::format("{}: binding {} ('{}', {}) is not one the rectify pass provides ({}textures, "
                                    "{} storage image)",
                                    kernel.name(), b.binding, b.name, to_string(b.type), provided, kOutput));
        }
        if (input != inputs_.end() && !input->uploaded)
            return fail(fmt::format("{}: dispatch before '{}' was uploaded", kernel.name(), wanted));
        bound.push_back(
            {b.binding,
             BoundImage{texture->view, storage ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                        storage || separate ? VK_NULL_HANDLE : sampler}});
    }
    if (auto ok = kernel_sets_.write(kernel, set, bound); !ok) return std::unexpected(ok.error());
    // Push constants by name, as the registry lays them out: every member needs a value of its size.
    std::vector<std::byte> push(kernel.push_constant_size());
    for (const Kernel::PushConstant& p : kernel.push_constants()) {
        auto given = std::find_if(values.begin(), values.end(), [&](const auto& v) { return v.name == p.name; });
        const std::size_t words = given == values.end() ? 0 : given->values.size() + given->uints.size();
        if (given == values.end() || words * 4 != p.size || p.offset + p.size > push.size() ||
            (!given->values.empty() && !given->uints.empty()))
            return fail(fmt::format("{}: push constant '{}' ({} bytes at {}) has no value of that size from the caller",
                                    kernel.name(), p.name, p.size, p.offset));
        if (given->uints.empty())
            std::memcpy(push.data() + p.offset, given->values.data(), p.size);
        else
            std::memcpy(push.data() + p.offset, given->uints.data(), p.size);
    }
    for (const PushConstantValue& v : values)
        if (std::none_of(kernel.push_constants().begin(), kernel.push_constants().end(),
                         [&](const auto& p) { return p.name == v.name; }))
            return fail(fmt::format("{}: has no push constant '{}'", kernel.name(), v.name));

    const uint32_t groups_x = (width_ + kernel.local_size()[0] - 1) / kernel.local_size()[0];
    const uint32_t groups_y = (height_ + kernel.local_size()[1] - 1) / kernel.local_size()[1];
    auto wall = commands_->run([&](VkCommandBuffer cb) {
        // The output's previous contents are not needed: every pixel is written.
        image_barrier(cb, output.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 0,
                      VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.pipeline());
        vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.layout(), 0, 1, &set, 0, nullptr);
        if (!push.empty())
            vkCmdPushConstants(cb, kernel.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, static_cast<uint32_t>(push.size()),
                               push.data());
        if (timestamps_) {
            vkCmdResetQueryPool(cb, timestamps_, 0, 2);
            vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps_, 0);
        }
        vkCmdDispatch(cb, groups_x, groups_y, 1);
        if (timestamps_) vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps_, 1);
    });
    if (!wall) return std::unexpected(wall.error());
    dispatched_ = true;
    half_written_ = half;
    output_layout_ = VK_IMAGE_LAYOUT_GENERAL;

    DispatchTiming timing{*wall, std::numeric_limits<double>::quiet_NaN()};
    if (timestamps_) {
        uint64_t ticks[2];
        KDOP_VK_TRY(vkGetQueryPoolResults(device, timestamps_, 0, 2, sizeof(ticks), ticks, sizeof(uint64_t),
                                          VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
        timing.device_ms = double(ticks[1] - ticks[0]) * context_.properties().limits.timestampPeriod * 1e-6;
    }
    return timing;
}

// The output, written by the last dispatch (or already copied), ready to be read by a transfer.
void RectifyPass::output_to_transfer_source(VkCommandBuffer cb) {
    if (output_layout_ == VK_IMAGE_LAYOUT_GENERAL)
        image_barrier(cb, written().image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT);
    output_layout_ = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL; // reads after reads need no barrier
}

Result<Image> RectifyPass::download() {
    if (!dispatched_) return fail("download before any dispatch");
    auto copied = commands_->run([&](VkCommandBuffer cb) {
        output_to_transfer_source(cb);
        VkBufferImageCopy copy = whole_image(width_, height_, 0);
        vkCmdCopyImageToBuffer(cb, written().image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer(), 1, &copy);
        host_read_barrier(cb, readback_.buffer());
    });
    if (!copied) return std::unexpected(copied.error());
    // Filled straight from the mapped buffer: one pass over the pixels, none to clear them first.
    Image out;
    out.width = width_, out.height = height_;
    const std::size_t pixels = std::size_t(width_) * height_;
    if (half_written_) {
        // Every half is a float exactly.
        const auto* mapped = static_cast<const std::uint16_t*>(readback_.mapped());
        out.pixels.resize(pixels);
        for (std::size_t i = 0; i < 4 * pixels; ++i) (&out.pixels[0].x)[i] = glm::unpackHalf1x16(mapped[i]);
        return out;
    }
    const auto* mapped = static_cast<const glm::vec4*>(readback_.mapped());
    out.pixels.assign(mapped, mapped + pixels);
    return out;
}

Result<RectifyPass::Input*> RectifyPass::input(std::string_view name) {
    auto it = std::find_if(inputs_.begin(), inputs_.end(), [&](const Input& in) { return in.name == name; });
    if (it == inputs_.end()) return fail(fmt::format("the rectify pass has no input '{}'", name));
    return &*it;
}

Result<void> RectifyPass::add_slots(std::string_view name, std::size_t count) {
    auto in = input(name);
    if (!in) return std::unexpected(in.error());
    if (count == 0 || (*in)->slots.size() != 1)
        return fail(fmt::format("'{}': slots are added once, at least one", name));
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    (*in)->slots.resize(count);
    for (std::size_t i = 1; i < count; ++i)
        if (auto ok = create_texture((*in)->slots[i], vk_format(format_, (*in)->channels), usage, (*in)->width,
                                     (*in)->height);
            !ok)
            return ok;
    // Zero, not whatever the memory held: a first frame's blend weighs its history by 0, and 0 x NaN is NaN.
    auto cleared = commands_->run([&](VkCommandBuffer cb) {
        const VkClearColorValue zero{};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        for (const Texture& t : (*in)->slots) {
            image_barrier(cb, t.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                          VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT);
            vkCmdClearColorImage(cb, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &all);
            image_barrier(cb, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                          VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
        }
    });
    if (!cleared) return std::unexpected(cleared.error());
    (*in)->selected = 0;
    (*in)->uploaded = true;
    return {};
}

Result<void> RectifyPass::select_slot(std::string_view name, std::size_t slot) {
    auto in = input(name);
    if (!in) return std::unexpected(in.error());
    if (slot >= (*in)->slots.size()) return fail(fmt::format("'{}': slot {} of {}", name, slot, (*in)->slots.size()));
    (*in)->selected = slot;
    return {};
}

Result<void> RectifyPass::copy_output_to(std::string_view name) {
    auto in = input(name);
    if (!in) return std::unexpected(in.error());
    if (!dispatched_) return fail("a copy of the output before any dispatch");
    if (format_ != TextureFormat::rgba32f || (*in)->channels != 4)
        return fail(fmt::format("'{}' is {} with {} channels, and the output copies only into rgba32f", name,
                                to_string(format_), (*in)->channels));
    if ((*in)->width != width_ || (*in)->height != height_)
        return fail(
            fmt::format("'{}' is {}x{}, and the output {}x{}", name, (*in)->width, (*in)->height, width_, height_));
    const Texture& into = (*in)->texture();
    // A texture never uploaded holds nothing to keep.
    const VkImageLayout was = (*in)->uploaded ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED;
    auto copied = commands_->run([&](VkCommandBuffer cb) {
        output_to_transfer_source(cb);
        // The last dispatch may have read this texture: its reads come before the copy's writes.
        image_barrier(cb, into.image, was, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        if (half_written_) {
            // A blit of one size converts the format texel for texel; half to float is exact.
            VkImageBlit blit{};
            blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            blit.srcOffsets[1] = blit.dstOffsets[1] = {std::int32_t(width_), std::int32_t(height_), 1};
            vkCmdBlitImage(cb, half_output_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, into.image,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
        } else {
            VkImageCopy copy{};
            copy.srcSubresource = copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            copy.extent = {width_, height_, 1};
            vkCmdCopyImage(cb, output_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, into.image,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        }
        image_barrier(cb, into.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
    });
    if (!copied) return std::unexpected(copied.error());
    // Only the selected slot is filled: where there are others, they were cleared by add_slots().
    (*in)->uploaded = true;
    return {};
}

Result<VkImageView> RectifyPass::view_to_sample(std::string_view name) {
    auto in = input(name);
    if (!in) return std::unexpected(in.error());
    if (!(*in)->uploaded)
        return fail(fmt::format("'{}' holds nothing yet: nothing was uploaded or copied there", name));
    return (*in)->texture().view;
}

Result<std::vector<VkImage>> RectifyPass::images_to_fill(std::span<const std::string_view> names) {
    if (format_ != TextureFormat::rgba32f)
        return fail(fmt::format("a {} pass's inputs are filled by uploads only", to_string(format_)));
    std::vector<VkImage> images;
    for (std::string_view name : names) {
        auto in = input(name);
        if (!in) return std::unexpected(in.error());
        images.push_back((*in)->texture().image);
        (*in)->uploaded = true;
    }
    return images;
}

void RectifyPass::destroy(Texture& t) {
    vkDestroyImageView(context_.device(), t.view, nullptr);
    vkDestroyImage(context_.device(), t.image, nullptr);
    vkFreeMemory(context_.device(), t.memory, nullptr);
}

RectifyPass::~RectifyPass() {
    VkDevice device = context_.device();
    vkDeviceWaitIdle(device);
    vkDestroyQueryPool(device, timestamps_, nullptr);
    vkDestroySampler(device, sampler_, nullptr);
    vkDestroySampler(device, linear_sampler_, nullptr);
    for (Input& in : inputs_)
        for (Texture& t : in.slots) destroy(t);
    destroy(output_);
    if (half_output_.image) destroy(half_output_);
}

Result<Image> rectify(const Context& context, const Variant& variant, const Image& current, const Image& history,
                      TextureFormat format, float gamma) {
    if (current.width != history.width || current.height != history.height)
        return fail(fmt::format("current is {}x{} but history is {}x{}", current.width, current.height, history.width,
                                history.height));
    auto kernel = Kernel::create(context, variant);
    if (!kernel) return std::unexpected(kernel.error());
    auto pass = RectifyPass::create(context, current.width, current.height, format);
    if (!pass) return std::unexpected(pass.error());
    if (auto ok = (*pass)->upload(current, history); !ok) return std::unexpected(ok.error());
    if (auto timing = (*pass)->dispatch(**kernel, gamma); !timing) return std::unexpected(timing.error());
    return (*pass)->download();
}

} // namespace kdop
