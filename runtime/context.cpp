#include "runtime/context.h"

#include "runtime/vulkan_error.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <link.h>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// Keeps the Vulkan drivers the loader has opened (Mesa's libvulkan_*.so) loaded until the process
// ends, where the loader would unload them with the last instance. Mesa's lavapipe keeps memory in
// its globals: unloaded, LeakSanitizer takes that memory for a leak of kdop's, with no frame it can
// name (found when kdop stopped loading OpenImageIO's 260 libraries at start, which had kept the
// driver loaded by chance). A later context in the same process then also finds it loaded.
void keep_drivers_loaded() {
    std::vector<std::string> drivers;
    dl_iterate_phdr(
        [](dl_phdr_info* info, std::size_t, void* found) {
            const std::string_view name = info->dlpi_name;
            if (name.find("/libvulkan_") != std::string_view::npos)
                static_cast<std::vector<std::string>*>(found)->emplace_back(name);
            return 0;
        },
        &drivers);
    // Outside the iteration, which holds the loader's lock. The handle is never closed.
    for (const std::string& driver : drivers) dlopen(driver.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
}

bool has_layer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    for (const VkLayerProperties& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

} // namespace

VKAPI_ATTR VkBool32 VKAPI_CALL Context::on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                              VkDebugUtilsMessageTypeFlagsEXT,
                                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                              void* self) {
    auto* context = static_cast<Context*>(self);
    std::lock_guard lock(context->messages_mutex_);
    context->messages_.emplace_back(data->pMessage ? data->pMessage : "(no message)");
    return VK_FALSE;
}

namespace {

// "Mesa 22.3.6 (llvmpipe)"-style text from VK_KHR_driver_properties where the device has it (core
// in 1.2), else the raw version numbers. For reports: which driver produced a measurement.
std::string driver_description(VkPhysicalDevice device, const VkPhysicalDeviceProperties& p) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
    const std::string api = fmt::format("Vulkan {}.{}.{}", VK_API_VERSION_MAJOR(p.apiVersion),
                                        VK_API_VERSION_MINOR(p.apiVersion), VK_API_VERSION_PATCH(p.apiVersion));
    for (const VkExtensionProperties& e : extensions) {
        if (std::string_view(e.extensionName) != VK_KHR_DRIVER_PROPERTIES_EXTENSION_NAME) continue;
        VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
        VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
        vkGetPhysicalDeviceProperties2(device, &properties);
        return fmt::format("{} {}, {}", driver.driverName, driver.driverInfo, api);
    }
    return fmt::format("driver version {:#x}, {}", p.driverVersion, api);
}

} // namespace

Result<std::unique_ptr<Context>> Context::create(const ContextOptions& options) {
    std::unique_ptr<Context> c(new Context);

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "kdop";
    app.apiVersion = options.api_version;
    VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instance_info.pApplicationInfo = &app;

    VkDebugUtilsMessengerCreateInfoEXT messenger_info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger_info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger_info.pfnUserCallback = &Context::on_validation_message;
    messenger_info.pUserData = c.get();
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    if (options.validation) {
        if (!has_layer(kValidationLayer))
            return fail(fmt::format("the Vulkan validation layer {} is not installed (Debian: vulkan-validationlayers)",
                                    kValidationLayer));
        instance_info.enabledLayerCount = 1;
        instance_info.ppEnabledLayerNames = &kValidationLayer;
        instance_info.enabledExtensionCount = 1;
        instance_info.ppEnabledExtensionNames = &extension;
        instance_info.pNext = &messenger_info; // also reports problems in vkCreateInstance itself
    }
    // What a user without a driver reads, instead of a bare VK_ERROR_INCOMPATIBLE_DRIVER: what is
    // missing, what to do, and what works without it.
    if (const VkResult created = vkCreateInstance(&instance_info, nullptr, &c->instance_); created != VK_SUCCESS) {
        const char* files =
            std::getenv("VK_DRIVER_FILES") ? std::getenv("VK_DRIVER_FILES") : std::getenv("VK_ICD_FILENAMES");
        return fail(fmt::format(
            "no Vulkan driver could be loaded (vkCreateInstance: {}). kdop runs on Mesa's lavapipe by default: install "
            "it (Debian: apt-get install mesa-vulkan-drivers), or name another installed driver's manifest in "
            "VK_DRIVER_FILES{}. Without a device, kdop list, gen, show, textures, flip --cpu, optimize (without "
            "--target-ghosting and --lavapipe-cost) and scene (of the 2-D scenes) still work, and so does kdop-gen",
            vk_result_text(created), files ? fmt::format(" (now: {})", files) : std::string()));
    }
    keep_drivers_loaded();
    if (options.validation) {
        auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(c->instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!create_messenger) return fail("vkCreateDebugUtilsMessengerEXT is not available");
        KDOP_VK_TRY(create_messenger(c->instance_, &messenger_info, nullptr, &c->messenger_));
    }

    uint32_t count = 0;
    KDOP_VK_TRY(vkEnumeratePhysicalDevices(c->instance_, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    KDOP_VK_TRY(vkEnumeratePhysicalDevices(c->instance_, &count, devices.data()));

    std::string wanted = options.device;
    if (wanted.empty())
        if (const char* env = std::getenv("KDOP_DEVICE")) wanted = env;
    std::vector<std::string> names;
    // "gpu": the first discrete GPU, else the first integrated or virtual one: whatever the machine
    // has that is not a CPU device, for a script that runs on any GPU machine.
    const bool any_gpu = wanted == "gpu";
    auto is_gpu = [](VkPhysicalDeviceType t, bool discrete_only) {
        return t == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU ||
               (!discrete_only &&
                (t == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU || t == VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU));
    };
    bool has_discrete = false;
    for (VkPhysicalDevice d : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(d, &p);
        has_discrete = has_discrete || p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
    }
    for (VkPhysicalDevice d : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(d, &p);
        names.emplace_back(p.deviceName);
        bool match = any_gpu          ? is_gpu(p.deviceType, has_discrete)
                     : wanted.empty() ? p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU
                                      : names.back().find(wanted) != std::string::npos;
        if (match && !c->physical_) {
            c->physical_ = d;
            c->properties_ = p;
            c->device_name_ = p.deviceName;
        }
    }
    if (c->physical_ && c->properties_.apiVersion < options.api_version)
        return fail(fmt::format("{} supports Vulkan {}.{}, and Vulkan {}.{} was asked for", c->device_name_,
                                VK_API_VERSION_MAJOR(c->properties_.apiVersion),
                                VK_API_VERSION_MINOR(c->properties_.apiVersion),
                                VK_API_VERSION_MAJOR(options.api_version), VK_API_VERSION_MINOR(options.api_version)));
    if (!c->physical_) {
        std::string available = names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "));
        return fail(
            wanted.empty()
                ? fmt::format("no CPU Vulkan device (lavapipe; Debian: mesa-vulkan-drivers); available devices: {}",
                              available)
            : any_gpu
                ? fmt::format("no Vulkan GPU (a CPU device such as lavapipe is not one); available devices: {}",
                              available)
                : fmt::format("no Vulkan device whose name contains '{}'; available devices: {}", wanted, available));
    }

    c->driver_info_ = driver_description(c->physical_, c->properties_);

    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(c->physical_, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(c->physical_, &family_count, families.data());
    // A family with graphics too where there is one (the first family, on every device seen), so
    // that a caller can also draw on the queue; else the first with compute.
    bool found = false;
    for (VkQueueFlags wanted :
         {VkQueueFlags(VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT), VkQueueFlags(VK_QUEUE_COMPUTE_BIT)})
        for (uint32_t i = 0; i < family_count && !found; ++i)
            if ((families[i].queueFlags & wanted) == wanted) {
                c->queue_family_ = i;
                c->queue_flags_ = families[i].queueFlags;
                found = true;
            }
    if (!found) return fail(fmt::format("{} has no compute queue", c->device_name_));

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = c->queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    KDOP_VK_TRY(vkCreateDevice(c->physical_, &device_info, nullptr, &c->device_));
    vkGetDeviceQueue(c->device_, c->queue_family_, 0, &c->queue_);

    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = c->queue_family_;
    KDOP_VK_TRY(vkCreateCommandPool(c->device_, &pool_info, nullptr, &c->command_pool_));
    return c;
}

Context::~Context() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        vkDestroyCommandPool(device_, command_pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
}

Result<uint32_t> Context::memory_type(uint32_t type_bits, VkMemoryPropertyFlags flags) const {
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory);
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & flags) == flags) return i;
    return fail(fmt::format("{} has no memory type with flags 0x{:x} among 0x{:x}", device_name_, flags, type_bits));
}

std::vector<std::string> Context::validation_messages() const {
    std::lock_guard lock(messages_mutex_);
    return messages_;
}

} // namespace kdop
