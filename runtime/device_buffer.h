// A Vulkan buffer with memory of its own, released with it: the storage every device pass works
// in. Host-visible buffers are mapped for their lifetime (what the host writes or reads back);
// device buffers take device-local memory (the working data no host ever touches). On lavapipe
// both are the same system memory; on a discrete GPU the difference is the PCIe bus.
#pragma once

#include "core/result.h"
#include "runtime/context.h"

#include <vulkan/vulkan.h>

namespace kdop {

class DeviceBuffer {
public:
    enum class Memory {
        device, // device-local
        host,   // host-visible and coherent (device-local too where the device has such memory), mapped
    };

    // A buffer of `size` bytes (at least 1) for `usage`; sizes above the device's
    // maxStorageBufferRange are refused for storage buffers, naming `what`.
    static Result<DeviceBuffer> create(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage,
                                       Memory memory, const char* what);

    DeviceBuffer() = default;
    DeviceBuffer(DeviceBuffer&& other) noexcept { *this = std::move(other); }
    DeviceBuffer& operator=(DeviceBuffer&& other) noexcept;
    DeviceBuffer(const DeviceBuffer&) = delete;
    DeviceBuffer& operator=(const DeviceBuffer&) = delete;
    ~DeviceBuffer() { release(); }

    VkBuffer buffer() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; } // null for device memory

private:
    void release();

    VkDevice device_ = VK_NULL_HANDLE;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

// Makes what transfers wrote to `buffer` visible to the host once the submission's fence is
// waited on: the last command of every pass that reads results back.
void host_read_barrier(VkCommandBuffer cb, VkBuffer buffer);

} // namespace kdop
