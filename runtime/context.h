// A Vulkan instance and device with one compute queue (graphics too where the device has it):
// the start of every GPU run.
//
// The device is Mesa's lavapipe by default, chosen as the first device of type CPU (not by
// index, which depends on what else is installed). ContextOptions::device or the KDOP_DEVICE
// environment variable pick another by a substring of its name ("NVIDIA", "llvmpipe").
// With validation on, the Khronos validation layer checks every call and the messages it
// reports are collected for the caller (tests fail on any).
#pragma once

#include "core/result.h"

#include <vulkan/vulkan.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace kdop {

struct ContextOptions {
    std::string device;      // substring of the device name; empty: KDOP_DEVICE, then the first CPU device
    bool validation = false; // enable VK_LAYER_KHRONOS_validation
    // The Vulkan version the instance is created for, which the device must support: 1.1 runs every
    // variant kdop builds by default; 1.3 runs the SPIR-V 1.6 of TARGET_ENV vulkan1.3.
    std::uint32_t api_version = VK_API_VERSION_1_1;
};

class Context {
public:
    static Result<std::unique_ptr<Context>> create(const ContextOptions& options);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return instance_; }
    VkDevice device() const { return device_; }
    VkPhysicalDevice physical_device() const { return physical_; }
    VkQueue queue() const { return queue_; }
    uint32_t queue_family() const { return queue_family_; }
    VkQueueFlags queue_flags() const { return queue_flags_; } // compute, and graphics where the device has it
    VkCommandPool command_pool() const { return command_pool_; }
    const std::string& device_name() const { return device_name_; }
    const std::string& driver_info() const {
        return driver_info_;
    } // e.g. "llvmpipe Mesa 22.3.6 (LLVM 15.0.6), Vulkan 1.3.230"
    const VkPhysicalDeviceProperties& properties() const { return properties_; }

    // A memory type allowed by `type_bits` with all of `flags`.
    Result<uint32_t> memory_type(uint32_t type_bits, VkMemoryPropertyFlags flags) const;

    // Messages the validation layer reported (warnings and errors), oldest first.
    std::vector<std::string> validation_messages() const;

private:
    Context() = default;
    static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                                VkDebugUtilsMessageTypeFlagsEXT types,
                                                                const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                                void* self);

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    VkQueueFlags queue_flags_ = 0;
    VkCommandPool command_pool_ = VK_NULL_HANDLE;
    std::string device_name_;
    std::string driver_info_;
    VkPhysicalDeviceProperties properties_{};
    mutable std::mutex messages_mutex_;
    std::vector<std::string> messages_;
};

} // namespace kdop
