#include "generator/target_env.h"

namespace kdop {

std::string_view to_string(TargetEnv env) {
    switch (env) {
    case TargetEnv::vulkan1_0: return "vulkan1.0";
    case TargetEnv::vulkan1_1: return "vulkan1.1";
    case TargetEnv::vulkan1_2: return "vulkan1.2";
    case TargetEnv::vulkan1_3: return "vulkan1.3";
    }
    return "";
}

std::optional<TargetEnv> parse_target_env(std::string_view name) {
    for (TargetEnv env : kAllTargetEnvs)
        if (to_string(env) == name) return env;
    return std::nullopt;
}

std::uint32_t spirv_version_word(TargetEnv env) {
    // Vulkan 1.0 takes SPIR-V 1.0, 1.1 up to 1.3, 1.2 up to 1.5, 1.3 up to 1.6 (the Vulkan
    // specification's "Versions" appendix).
    switch (env) {
    case TargetEnv::vulkan1_0: return 0x00010000;
    case TargetEnv::vulkan1_1: return 0x00010300;
    case TargetEnv::vulkan1_2: return 0x00010500;
    case TargetEnv::vulkan1_3: return 0x00010600;
    }
    return 0;
}

} // namespace kdop
