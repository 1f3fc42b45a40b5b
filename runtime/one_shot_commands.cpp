#include "runtime/one_shot_commands.h"

#include "runtime/vulkan_error.h"

#include <chrono>
#include <cstdint>

namespace kdop {

Result<std::unique_ptr<OneShotCommands>> OneShotCommands::create(const Context& context) {
    std::unique_ptr<OneShotCommands> c(new OneShotCommands(context));
    VkCommandBufferAllocateInfo cb{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cb.commandPool = context.command_pool();
    cb.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cb.commandBufferCount = 1;
    KDOP_VK_TRY(vkAllocateCommandBuffers(context.device(), &cb, &c->commands_));
    VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    KDOP_VK_TRY(vkCreateFence(context.device(), &fence, nullptr, &c->fence_));
    return c;
}

OneShotCommands::~OneShotCommands() {
    VkDevice device = context_.device();
    vkDestroyFence(device, fence_, nullptr);
    if (commands_) vkFreeCommandBuffers(device, context_.command_pool(), 1, &commands_);
}

Result<double> OneShotCommands::run(const std::function<void(VkCommandBuffer)>& record) {
    VkDevice device = context_.device();
    KDOP_VK_TRY(vkResetCommandBuffer(commands_, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    KDOP_VK_TRY(vkBeginCommandBuffer(commands_, &begin));
    record(commands_);
    KDOP_VK_TRY(vkEndCommandBuffer(commands_));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands_;
    KDOP_VK_TRY(vkResetFences(device, 1, &fence_));
    const auto start = std::chrono::steady_clock::now();
    KDOP_VK_TRY(vkQueueSubmit(context_.queue(), 1, &submit, fence_));
    KDOP_VK_TRY(vkWaitForFences(device, 1, &fence_, VK_TRUE, UINT64_MAX));
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace kdop
