#include "generator/spirv_tools.h"

#include "generator/glsl_compiler.h"
#include "generator/spirv_module.h"

#include <fmt/format.h>
#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/optimizer.hpp>

namespace kdop {
namespace {

spv_target_env spirv_tools_env(TargetEnv env) {
    switch (env) {
    case TargetEnv::vulkan1_0: return SPV_ENV_VULKAN_1_0;
    case TargetEnv::vulkan1_1: return SPV_ENV_VULKAN_1_1;
    case TargetEnv::vulkan1_2: return SPV_ENV_VULKAN_1_2;
    case TargetEnv::vulkan1_3: return SPV_ENV_VULKAN_1_3;
    }
    return SPV_ENV_VULKAN_1_0;
}

// Collects SPIRV-Tools messages; the position's index is the 1-based ordinal of the instruction.
struct MessageLog {
    std::vector<std::pair<std::size_t, std::string>> messages;
    spvtools::MessageConsumer consumer() {
        return [this](spv_message_level_t level, const char*, const spv_position_t& position, const char* message) {
            if (level <= SPV_MSG_ERROR) messages.emplace_back(position.index, message);
        };
    }
};

Result<std::vector<std::uint32_t>> run_passes(const std::vector<std::uint32_t>& words, std::string_view name,
                                              TargetEnv env, std::string_view what,
                                              void (*register_passes)(spvtools::Optimizer&)) {
    spvtools::Optimizer optimizer(spirv_tools_env(env));
    MessageLog log;
    optimizer.SetMessageConsumer(log.consumer());
    register_passes(optimizer);
    std::vector<std::uint32_t> out;
    if (!optimizer.Run(words.data(), words.size(), &out)) {
        std::string text = fmt::format("{}: SPIR-V {} failed:\n", name, what);
        for (const auto& [index, message] : log.messages) text += fmt::format("    {}\n", message);
        return fail(text);
    }
    return out;
}

} // namespace

Result<void> validate_spirv(const std::vector<std::uint32_t>& words, std::string_view source, std::string_view name,
                            std::string_view stage, TargetEnv env) {
    spvtools::SpirvTools tools(spirv_tools_env(env));
    MessageLog log;
    tools.SetMessageConsumer(log.consumer());
    if (tools.Validate(words)) return {};
    std::string text;
    for (const auto& [index, message] : log.messages)
        text += glsl_diagnostic(source, name, glsl_line_of_instruction(words, index),
                                fmt::format("error: SPIR-V validation of the {} failed: {}", stage, message));
    return fail(text.empty() ? fmt::format("{}: SPIR-V validation of the {} failed", name, stage) : text);
}

Result<std::vector<std::uint32_t>> optimize_spirv(const std::vector<std::uint32_t>& words, std::string_view name,
                                                  TargetEnv env) {
    return run_passes(words, name, env, "optimization", [](spvtools::Optimizer& o) { o.RegisterPerformancePasses(); });
}

Result<std::vector<std::uint32_t>> shipped_spirv(const std::vector<std::uint32_t>& words, std::string_view name,
                                                 TargetEnv env, bool strip_names) {
    if (!strip_names) return without_line_info(words);
    return run_passes(words, name, env, "debug-information stripping",
                      [](spvtools::Optimizer& o) { o.RegisterPass(spvtools::CreateStripDebugInfoPass()); });
}

} // namespace kdop
