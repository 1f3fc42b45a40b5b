// Runs this example's two TAA resolves, in GLSL and in their HLSL ports, on a Vulkan device (the one whose name
// contains argv[1], default "llvmpipe", Mesa's lavapipe) as an engine would, with VK_NO_PROTOTYPES: the loader is
// opened here and every call goes through function pointers, as with volk. With the Khronos
// validation layer on when it is installed, it prints what the registry reflected, how far the
// clip moved the history, and whether the four resolves (compute and fragment, GLSL and HLSL) agree;
// then it upscales a moving, jittered frame 2x over a few frames with the TAAU resolve
// (upscale_compute.comp, hlsl_upscale_compute.cs.hlsl) and prints whether GLSL and HLSL agree.
// It exits non-zero when any do not, or when the validation layer reported anything.
#include "engine_resolve_kdop_variants.h"
#include "resolve_runner.h"

#include <kdop/vulkan_pipeline.h>

#include <dlfcn.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace {

std::atomic<int> validation_messages{0};

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
    std::fprintf(stderr, "validation: %s\n", data->pMessage);
    ++validation_messages;
    return VK_FALSE;
}

int fail(const char* what, VkResult result) {
    std::fprintf(stderr, "%s failed: VkResult %d\n", what, static_cast<int>(result));
    return 1;
}

// A frame with edges and fine detail (a hash per pixel over two bands of color), deterministic;
// `shift` moves it that many pixels to the left.
std::vector<float> test_frame(std::uint32_t width, std::uint32_t height, std::uint32_t salt, std::uint32_t shift = 0) {
    std::vector<float> rgba(std::size_t(width) * height * 4);
    for (std::uint32_t y = 0; y < height; ++y)
        for (std::uint32_t x0 = 0; x0 < width; ++x0) {
            const std::uint32_t x = x0 + shift;
            std::uint32_t h = (x * 73856093u) ^ (y * 19349663u) ^ (salt * 83492791u);
            h ^= h >> 13;
            h *= 0x5bd1e995u;
            h ^= h >> 15;
            const float noise = float(h & 0xffffu) / 65535.0f;
            const bool band = (x / 8 + y / 6) % 2 == 0;
            float* p = &rgba[(std::size_t(y) * width + x0) * 4];
            p[0] = band ? 0.2f + 0.3f * noise : 0.7f;
            p[1] = band ? 0.5f : 0.3f + 0.2f * noise;
            p[2] = 0.25f + 0.5f * noise * noise;
            p[3] = 1.0f;
        }
    return rgba;
}

} // namespace

int main(int argc, char** argv) {
    const char* wanted_device = argc > 1 ? argv[1] : "llvmpipe";
    const kdop::VariantList registry = engine_resolve_kdop::variants();
    const engine::Shaders glsl{registry.find("resolve_compute"), registry.find("fullscreen"),
                               registry.find("resolve_fragment")};
    const engine::Shaders hlsl{registry.find("hlsl_resolve_compute"), registry.find("hlsl_fullscreen"),
                               registry.find("hlsl_resolve_fragment")};
    const kdop::Variant* upscalers[] = {registry.find("upscale_compute"), registry.find("hlsl_upscale_compute")};
    const engine::Shaders& shaders = glsl;
    for (const kdop::Variant* entry : {glsl.compute, glsl.vertex, glsl.fragment, hlsl.compute, hlsl.vertex,
                                       hlsl.fragment, upscalers[0], upscalers[1]}) {
        if (!entry) {
            std::fprintf(stderr, "a shader of the example is not embedded\n");
            return 1;
        }
        std::printf("%s: %s shader, %u binding(s)\n", entry->name, kdop::to_string(entry->stage), entry->binding_count);
        for (std::uint32_t i = 0; i < entry->binding_count; ++i) {
            const kdop::DescriptorBinding& b = entry->bindings[i];
            std::printf("  set %u binding %u: %s (%s", b.set, b.binding, b.name, kdop::to_string(b.type));
            if (b.count != 1) std::printf(" x%u", b.count);
            if (b.block_size) std::printf(", %u bytes", b.block_size);
            if (b.format) std::printf(", VkFormat %u", b.format);
            std::printf(")\n");
        }
        if (entry->push_constant_size) std::printf("  push constants: %u bytes\n", entry->push_constant_size);
    }

    // The loader, opened as volk opens it.
    void* loader = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!loader) {
        std::fprintf(stderr, "cannot open libvulkan.so.1: %s\n", dlerror());
        return 1;
    }
    const auto get_instance_proc_addr =
        reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(loader, "vkGetInstanceProcAddr"));
#define GLOBAL(name) const auto name = reinterpret_cast<PFN_##name>(get_instance_proc_addr(VK_NULL_HANDLE, #name))
    GLOBAL(vkCreateInstance);
    GLOBAL(vkEnumerateInstanceLayerProperties);
#undef GLOBAL

    std::uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    const char* validation_layer = "VK_LAYER_KHRONOS_validation";
    const bool validation = std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
        return std::strcmp(l.layerName, validation_layer) == 0;
    });
    const char* debug_extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "kdop engine_resolve example";
    app.apiVersion = VK_API_VERSION_1_3; // the resolves need 1.0; 1.3 for dynamic rendering where the device has it
    VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instance_info.pApplicationInfo = &app;
    instance_info.enabledLayerCount = validation ? 1 : 0;
    instance_info.ppEnabledLayerNames = &validation_layer;
    instance_info.enabledExtensionCount = validation ? 1 : 0;
    instance_info.ppEnabledExtensionNames = &debug_extension;
    VkInstance instance = VK_NULL_HANDLE;
    if (VkResult r = vkCreateInstance(&instance_info, nullptr, &instance); r != VK_SUCCESS)
        return fail("vkCreateInstance", r);
#define INSTANCE(name) const auto name = reinterpret_cast<PFN_##name>(get_instance_proc_addr(instance, #name))
    INSTANCE(vkDestroyInstance);
    INSTANCE(vkEnumeratePhysicalDevices);
    INSTANCE(vkGetPhysicalDeviceProperties);
    INSTANCE(vkGetPhysicalDeviceQueueFamilyProperties);
    INSTANCE(vkCreateDevice);
    INSTANCE(vkGetDeviceProcAddr);
    INSTANCE(vkCreateDebugUtilsMessengerEXT);
    INSTANCE(vkDestroyDebugUtilsMessengerEXT);
#undef INSTANCE

    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    if (validation) {
        VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
        info.messageSeverity =
            VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
        info.pfnUserCallback = on_message;
        if (VkResult r = vkCreateDebugUtilsMessengerEXT(instance, &info, nullptr, &messenger); r != VK_SUCCESS)
            return fail("vkCreateDebugUtilsMessengerEXT", r);
    }

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

    // One queue that draws and computes, as an engine's main queue does.
    vkGetPhysicalDeviceQueueFamilyProperties(chosen, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(chosen, &count, families.data());
    const VkQueueFlags wanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    std::uint32_t family = 0;
    while (family < count && (families[family].queueFlags & wanted) != wanted) ++family;
    if (family == count) {
        std::fprintf(stderr, "%s has no queue that draws and computes\n", properties.deviceName);
        return 1;
    }
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = family;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    // Dynamic rendering (Vulkan 1.3), where the device has it, for a second graphics pipeline below.
    const bool dynamic_rendering = properties.apiVersion >= VK_API_VERSION_1_3;
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    features13.dynamicRendering = VK_TRUE;
    VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device_info.pNext = dynamic_rendering ? &features13 : nullptr;
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    VkDevice device = VK_NULL_HANDLE;
    if (VkResult r = vkCreateDevice(chosen, &device_info, nullptr, &device); r != VK_SUCCESS)
        return fail("vkCreateDevice", r);
    const auto vkGetDeviceQueue =
        reinterpret_cast<PFN_vkGetDeviceQueue>(vkGetDeviceProcAddr(device, "vkGetDeviceQueue"));
    const auto vkDestroyDevice = reinterpret_cast<PFN_vkDestroyDevice>(vkGetDeviceProcAddr(device, "vkDestroyDevice"));
    VkQueue queue = VK_NULL_HANDLE;
    vkGetDeviceQueue(device, family, 0, &queue);

    // This frame, and a history that is this frame moved by the motion, with a ghost in it (a
    // saturated square that has left the scene): the clip must take the ghost out.
    const std::uint32_t width = 67, height = 45; // not multiples of the work group
    engine::Frames frames;
    frames.current = test_frame(width, height, 1);
    frames.history = frames.current;
    frames.motion = {3.0f, -2.0f};
    frames.current_weight = 0.1f;
    for (std::uint32_t y = 10; y < 26; ++y)
        for (std::uint32_t x = 20; x < 36; ++x) {
            float* p = &frames.history[(std::size_t(y) * width + x) * 4];
            p[0] = 1.0f, p[1] = 0.0f, p[2] = 1.0f;
        }

    int status = 0;
    // The helper's other graphics path: the same resolve drawn with dynamic rendering into an
    // rgba32f attachment (created and destroyed here; resolve_runner.cpp draws with a render pass).
    if (dynamic_rendering) {
        kdop::VariantVulkanFunctions vk;
        kdop::VariantPipeline pipeline;
        const VkFormat color = VK_FORMAT_R32G32B32A32_SFLOAT;
        kdop::GraphicsTargets targets;
        targets.color_formats = &color;
        targets.color_format_count = 1;
        VkResult r = kdop::load_variant_functions(device, vkGetDeviceProcAddr, vk);
        if (r == VK_SUCCESS)
            r = kdop::create_variant_graphics_pipeline(vk, device, *shaders.vertex, *shaders.fragment, targets,
                                                       pipeline);
        if (r != VK_SUCCESS) {
            std::fprintf(stderr, "dynamic rendering pipeline: %s (VkResult %d)\n",
                         pipeline.failure ? pipeline.failure : "failed", static_cast<int>(r));
            status = 1;
        } else {
            std::printf("dynamic rendering pipeline created\n");
            kdop::destroy_variant_pipeline(vk, device, pipeline);
        }
    } else {
        std::printf("dynamic rendering: %s has no Vulkan 1.3\n", properties.deviceName);
    }
    // Each language's two resolves, all four compared with the GLSL compute resolve.
    const engine::Device engine_device{instance, chosen, device, queue, family, get_instance_proc_addr};
    std::vector<float> first;
    for (const auto& [language, language_shaders] : {std::pair{"GLSL", &glsl}, std::pair{"HLSL", &hlsl}}) {
        std::string error;
        auto resolver = engine::Resolver::create(engine_device, *language_shaders, width, height, error);
        engine::Resolved resolved;
        if (resolver) error = resolver->resolve(frames, resolved);
        if (!error.empty()) {
            std::fprintf(stderr, "%s: %s\n", language, error.c_str());
            status = 1;
            continue;
        }
        std::printf("both %s resolves ran on %s (%ux%u)\n", language, properties.deviceName, width, height);
        if (first.empty()) first = resolved.compute;
        double largest_difference = 0, moved = 0, most_moved = 0;
        for (std::size_t i = 0; i < resolved.compute.size(); ++i)
            largest_difference = std::max({largest_difference, double(std::abs(resolved.compute[i] - first[i])),
                                           double(std::abs(resolved.fragment[i] - first[i]))});
        for (float d : resolved.clip_distance) {
            moved += d;
            most_moved = std::max(most_moved, double(d));
        }
        std::printf("%s: history moved by the clip: mean %.4f, largest %.4f\n", language,
                    moved / resolved.clip_distance.size(), most_moved);
        // Each is within 2e-4 of kdop's CPU reference on content like this (tests/engine_resolve_test.cpp).
        const bool agree = largest_difference <= 4e-4;
        std::printf("%s compute and fragment resolves %s with the GLSL compute resolve: largest difference %.2e\n",
                    language, agree ? "agree" : "DISAGREE", largest_difference);
        if (!agree) status = 1;
    }
    // The TAAU resolves, GLSL and HLSL: the frame above at about half the size, moving one input pixel to
    // the left a frame, jittered, upscaled 2x over a few frames, each from its own history.
    const std::uint32_t input_width = 34, input_height = 23;
    const float jitters[][2] = {{0.0f, -0.1667f}, {-0.25f, 0.1667f}, {0.25f, -0.3889f}, {-0.375f, -0.0556f}};
    std::vector<float> upscaled[2];
    for (int l = 0; l < 2; ++l) {
        std::string error;
        auto upscaler =
            engine::Upscaler::create(engine_device, *upscalers[l], input_width, input_height, width, height, error);
        engine::UpscaleFrames upscale;
        upscale.motion.assign(std::size_t(input_width) * input_height * 2, 0.0f);
        for (std::size_t i = 0; i < upscale.motion.size(); i += 2) upscale.motion[i] = 1.0f; // it was 1 to the right
        for (std::uint32_t f = 0; upscaler && error.empty() && f < std::size(jitters); ++f) {
            upscale.current = test_frame(input_width, input_height, 1, f);
            upscale.jitter = {jitters[f][0], jitters[f][1]};
            upscale.current_weight = f == 0 ? 1.0f : 0.1f;   // the first frame starts the history
            error = upscaler->resolve(upscale, upscaled[l]); // the next frame's history, kept on the device
        }
        if (!error.empty()) {
            std::fprintf(stderr, "%s: %s\n", upscalers[l]->name, error.c_str());
            status = 1;
        }
    }
    if (!upscaled[0].empty() && upscaled[0].size() == upscaled[1].size()) {
        double largest_difference = 0;
        for (std::size_t i = 0; i < upscaled[0].size(); ++i)
            largest_difference = std::max(largest_difference, double(std::abs(upscaled[0][i] - upscaled[1][i])));
        const bool agree = largest_difference <= 4e-4;
        std::printf("GLSL and HLSL TAAU resolves (%ux%u to %ux%u, %zu frames) %s: largest difference %.2e\n",
                    input_width, input_height, width, height, std::size(jitters), agree ? "agree" : "DISAGREE",
                    largest_difference);
        if (!agree) status = 1;
    }
    vkDestroyDevice(device, nullptr);
    if (messenger) vkDestroyDebugUtilsMessengerEXT(instance, messenger, nullptr);
    vkDestroyInstance(instance, nullptr);
    std::printf("validation layer %s, %d message(s)\n", validation ? "on" : "not installed",
                validation_messages.load());
    if (validation_messages.load() > 0) status = 1;
    dlclose(loader);
    return status;
}
