// Creates the TAA resolve's compute pipeline on a Vulkan device the way a renderer would: from the
// registry entry kdop_add_variants() embedded, with one call (kdop/vulkan_pipeline.h). Uses the
// device whose name contains argv[1] (default "llvmpipe", Mesa's lavapipe), else the first.
#include "taa_resolve_kdop_variants.h"

#include <kdop/vulkan_pipeline.h>

#include <cstdio>
#include <cstring>
#include <vector>

namespace {

int fail(const char* what, VkResult result) {
    std::fprintf(stderr, "%s failed: VkResult %d\n", what, static_cast<int>(result));
    return 1;
}

} // namespace

int main(int argc, char** argv) {
    const char* wanted_device = argc > 1 ? argv[1] : "llvmpipe";
    const kdop::Variant* resolve = taa_resolve_kdop::variants().find("taa_resolve");
    if (!resolve) {
        std::fprintf(stderr, "taa_resolve is not embedded\n");
        return 1;
    }

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "kdop taa_resolve example";
    app.apiVersion = VK_API_VERSION_1_0;
    VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instance_info.pApplicationInfo = &app;
    VkInstance instance = VK_NULL_HANDLE;
    if (VkResult r = vkCreateInstance(&instance_info, nullptr, &instance); r != VK_SUCCESS)
        return fail("vkCreateInstance", r);

    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> physical(count);
    vkEnumeratePhysicalDevices(instance, &count, physical.data());
    if (physical.empty()) {
        std::fprintf(stderr, "no Vulkan device\n");
        return 1;
    }
    VkPhysicalDevice chosen = physical[0];
    VkPhysicalDeviceProperties properties;
    for (VkPhysicalDevice d : physical) {
        vkGetPhysicalDeviceProperties(d, &properties);
        if (std::strstr(properties.deviceName, wanted_device)) chosen = d;
    }
    vkGetPhysicalDeviceProperties(chosen, &properties);

    // A queue family with compute; the renderer's own device would already have one.
    vkGetPhysicalDeviceQueueFamilyProperties(chosen, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(chosen, &count, families.data());
    uint32_t family = 0;
    while (family < count && !(families[family].queueFlags & VK_QUEUE_COMPUTE_BIT)) ++family;
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = family;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    VkDevice device = VK_NULL_HANDLE;
    if (VkResult r = vkCreateDevice(chosen, &device_info, nullptr, &device); r != VK_SUCCESS)
        return fail("vkCreateDevice", r);

    // The one call: set layouts, pipeline layout and pipeline from the registry's reflection.
    kdop::VariantPipeline pipeline;
    if (VkResult r = kdop::create_variant_pipeline(device, *resolve, pipeline); r != VK_SUCCESS)
        return fail("kdop::create_variant_pipeline", r);
    std::printf("%s: pipeline created on %s, %u descriptor set layout(s), local size %ux%u\n", resolve->name,
                properties.deviceName, pipeline.set_layout_count, resolve->local_size[0], resolve->local_size[1]);
    for (uint32_t i = 0; i < resolve->binding_count; ++i)
        std::printf("  set %u binding %u: %s (%s)\n", resolve->bindings[i].set, resolve->bindings[i].binding,
                    resolve->bindings[i].name, kdop::to_string(resolve->bindings[i].type));
    for (uint32_t i = 0; i < resolve->push_constant_count; ++i)
        std::printf("  push constant %s: %u bytes at %u\n", resolve->push_constants[i].name,
                    resolve->push_constants[i].size, resolve->push_constants[i].offset);

    kdop::destroy_variant_pipeline(device, pipeline);
    vkDestroyDevice(device, nullptr);
    vkDestroyInstance(instance, nullptr);
    return 0;
}
