#include "runtime/device_image.h"

#include "runtime/vulkan_error.h"

#include <fmt/format.h>

#include <utility>

namespace kdop {

Result<DeviceImage> DeviceImage::create(const Context& context, std::uint32_t width, std::uint32_t height,
                                        std::uint32_t layers, VkFormat format, VkImageUsageFlags usage,
                                        const char* what, VkImageAspectFlags aspect) {
    const auto& limits = context.properties().limits;
    if (width == 0 || height == 0 || layers == 0)
        return fail(fmt::format("{}: an empty {}x{} image of {} layers", what, width, height, layers));
    // Checked here rather than left to vkCreateImage, which is undefined (and a validation error)
    // beyond the limits.
    if (width > limits.maxImageDimension2D || height > limits.maxImageDimension2D)
        return fail(fmt::format("{}: a {}x{} image is larger than {} allows: at most {} pixels on a side", what, width,
                                height, context.device_name(), limits.maxImageDimension2D));
    if (layers > limits.maxImageArrayLayers)
        return fail(fmt::format("{}: {} layers; {} allows at most {}", what, layers, context.device_name(),
                                limits.maxImageArrayLayers));
    DeviceImage i;
    i.device_ = context.device();
    i.layers_ = layers;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = layers;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    KDOP_VK_TRY(vkCreateImage(i.device_, &info, nullptr, &i.image_));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(i.device_, i.image_, &req);
    auto type = context.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (!type) return fail(fmt::format("{}: {}", what, type.error().message));
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = *type;
    KDOP_VK_TRY(vkAllocateMemory(i.device_, &alloc, nullptr, &i.memory_));
    KDOP_VK_TRY(vkBindImageMemory(i.device_, i.image_, i.memory_, 0));
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = i.image_;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    view.format = format;
    view.subresourceRange = {aspect, 0, 1, 0, layers};
    KDOP_VK_TRY(vkCreateImageView(i.device_, &view, nullptr, &i.view_));
    return i;
}

DeviceImage& DeviceImage::operator=(DeviceImage&& other) noexcept {
    if (this != &other) {
        release();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        image_ = std::exchange(other.image_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        view_ = std::exchange(other.view_, VK_NULL_HANDLE);
        layers_ = std::exchange(other.layers_, 0);
    }
    return *this;
}

void DeviceImage::release() {
    if (!device_) return;
    vkDestroyImageView(device_, view_, nullptr);
    vkDestroyImage(device_, image_, nullptr);
    vkFreeMemory(device_, memory_, nullptr);
    device_ = VK_NULL_HANDLE;
}

void image_barrier(VkCommandBuffer cb, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags src_access,
                   VkAccessFlags dst_access, VkPipelineStageFlags src_stage, VkPipelineStageFlags dst_stage,
                   std::uint32_t layers) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers};
    vkCmdPipelineBarrier(cb, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

} // namespace kdop
