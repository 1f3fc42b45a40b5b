#include "runtime/device_buffer.h"

#include "runtime/vulkan_error.h"

#include <fmt/format.h>

#include <utility>

namespace kdop {

Result<DeviceBuffer> DeviceBuffer::create(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage,
                                          Memory memory, const char* what) {
    if (size == 0) return fail(fmt::format("{}: a buffer of 0 bytes", what));
    const VkDeviceSize range = context.properties().limits.maxStorageBufferRange;
    if ((usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && size > range)
        return fail(fmt::format("{}: needs a storage buffer of {} bytes; {} allows at most {}", what, size,
                                context.device_name(), range));
    DeviceBuffer b;
    b.device_ = context.device();
    b.size_ = size;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    KDOP_VK_TRY(vkCreateBuffer(b.device_, &info, nullptr, &b.buffer_));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(b.device_, b.buffer_, &req);
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    auto type = memory == Memory::device
                    ? context.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)
                    : context.memory_type(req.memoryTypeBits, host | VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (!type && memory == Memory::host) type = context.memory_type(req.memoryTypeBits, host);
    if (!type) return fail(fmt::format("{}: {}", what, type.error().message));
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = *type;
    KDOP_VK_TRY(vkAllocateMemory(b.device_, &alloc, nullptr, &b.memory_));
    KDOP_VK_TRY(vkBindBufferMemory(b.device_, b.buffer_, b.memory_, 0));
    if (memory == Memory::host) KDOP_VK_TRY(vkMapMemory(b.device_, b.memory_, 0, VK_WHOLE_SIZE, 0, &b.mapped_));
    return b;
}

DeviceBuffer& DeviceBuffer::operator=(DeviceBuffer&& other) noexcept {
    if (this != &other) {
        release();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        size_ = std::exchange(other.size_, 0);
        mapped_ = std::exchange(other.mapped_, nullptr);
    }
    return *this;
}

void DeviceBuffer::release() {
    if (!device_) return;
    vkDestroyBuffer(device_, buffer_, nullptr);
    vkFreeMemory(device_, memory_, nullptr); // unmaps
    device_ = VK_NULL_HANDLE;
}

void host_read_barrier(VkCommandBuffer cb, VkBuffer buffer) {
    VkBufferMemoryBarrier b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = buffer;
    b.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &b, 0,
                         nullptr);
}

} // namespace kdop
