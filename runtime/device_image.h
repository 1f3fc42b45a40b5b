// A Vulkan 2-D array image in device-local memory with a view of all its layers, released with
// it: the working planes of passes that read neighbors (flip/device_flip.h). An image rather than
// a storage buffer because lavapipe fetches texels for all lanes of a SIMD row at once but loads a
// storage buffer lane by lane wherever the lanes' addresses differ (docs/flip.md, "FLIP on the device").
#pragma once

#include "core/result.h"
#include "runtime/context.h"

#include <vulkan/vulkan.h>

#include <cstdint>

namespace kdop {

class DeviceImage {
public:
    // A width x height image of `layers` layers of `format`, for `usage`, in optimal tiling and the
    // undefined layout, its view of `aspect`; sizes beyond the device's limits are refused, naming
    // `what`.
    static Result<DeviceImage> create(const Context& context, std::uint32_t width, std::uint32_t height,
                                      std::uint32_t layers, VkFormat format, VkImageUsageFlags usage, const char* what,
                                      VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT);

    DeviceImage() = default;
    DeviceImage(DeviceImage&& other) noexcept { *this = std::move(other); }
    DeviceImage& operator=(DeviceImage&& other) noexcept;
    DeviceImage(const DeviceImage&) = delete;
    DeviceImage& operator=(const DeviceImage&) = delete;
    ~DeviceImage() { release(); }

    VkImage image() const { return image_; }
    VkImageView view() const { return view_; } // VK_IMAGE_VIEW_TYPE_2D_ARRAY, every layer
    std::uint32_t layers() const { return layers_; }

private:
    void release();

    VkDevice device_ = VK_NULL_HANDLE;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    std::uint32_t layers_ = 0;
};

// A barrier on the first `layers` layers of a color image (mip level 0), from layout `from` to `to`
// (which may be equal: a memory dependency only). RectifyPass's textures and DeviceImage's use it.
void image_barrier(VkCommandBuffer cb, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags src_access,
                   VkAccessFlags dst_access, VkPipelineStageFlags src_stage, VkPipelineStageFlags dst_stage,
                   std::uint32_t layers = 1);

} // namespace kdop
