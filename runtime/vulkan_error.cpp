#include "runtime/vulkan_error.h"

#include <fmt/format.h>
#include <vulkan/vulkan.hpp>

namespace kdop {

std::string vk_result_text(VkResult result) {
    // vulkan.hpp knows every VkResult by name; "ErrorOutOfHostMemory" reads as VK_ERROR_OUT_OF_HOST_MEMORY.
    std::string name = vk::to_string(static_cast<vk::Result>(result));
    std::string upper = "VK";
    for (char c : name) {
        if (std::isupper(static_cast<unsigned char>(c))) upper += '_';
        upper += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
    return fmt::format("{} ({})", upper, static_cast<int>(result));
}

std::unexpected<Error> vk_failure(std::string_view call, VkResult result) {
    std::string_view function = call.substr(0, call.find('('));
    return fail(fmt::format("{} failed: {}", function, vk_result_text(result)));
}

} // namespace kdop
