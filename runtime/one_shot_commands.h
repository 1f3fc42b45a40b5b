// One command buffer and one fence on the context's queue: record, submit, wait. What every
// device pass does with its work (a rectification, a FLIP evaluation): nothing overlaps the host,
// so each call returns with the results in memory.
#pragma once

#include "core/result.h"
#include "runtime/context.h"

#include <vulkan/vulkan.h>

#include <functional>
#include <memory>

namespace kdop {

class OneShotCommands {
public:
    static Result<std::unique_ptr<OneShotCommands>> create(const Context& context);
    ~OneShotCommands();
    OneShotCommands(const OneShotCommands&) = delete;
    OneShotCommands& operator=(const OneShotCommands&) = delete;

    // Records with `record`, submits and waits for the fence; returns the wall time from submit to
    // fence, in milliseconds.
    Result<double> run(const std::function<void(VkCommandBuffer)>& record);

private:
    explicit OneShotCommands(const Context& context) : context_(context) {}

    const Context& context_;
    VkCommandBuffer commands_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
};

} // namespace kdop
