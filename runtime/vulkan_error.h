// Every Vulkan call in the runtime is checked, always (not only in debug builds): a failure
// becomes an Error naming the call and its VkResult, e.g.
// "vkCreateComputePipelines failed: VK_ERROR_OUT_OF_HOST_MEMORY (-1)".
#pragma once

#include "core/result.h"

#include <vulkan/vulkan.h>

#include <string>
#include <string_view>

namespace kdop {

std::string vk_result_text(VkResult result);

// An Error for `call` (the call's source text; its function name is kept) having returned `result`.
std::unexpected<Error> vk_failure(std::string_view call, VkResult result);

} // namespace kdop

// Evaluates a Vulkan call and returns its failure from the enclosing function (which returns a
// Result) unless it returned VK_SUCCESS.
#define KDOP_VK_TRY(call)                                                                                              \
    do {                                                                                                               \
        if (VkResult kdop_vk_result_ = (call); kdop_vk_result_ != VK_SUCCESS)                                          \
            return ::kdop::vk_failure(#call, kdop_vk_result_);                                                         \
    } while (0)
