// The Vulkan version a variant's SPIR-V is built for: glslang's client and SPIR-V target, and the
// environment SPIRV-Tools optimizes and validates for. Vulkan 1.0 (SPIR-V 1.0), the default, runs
// on every Vulkan device; a later one lets a renderer that requires it get the SPIR-V version its
// other shaders use (1.1: SPIR-V 1.3, 1.2: 1.5, 1.3: 1.6, each the highest that version accepts).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace kdop {

enum class TargetEnv { vulkan1_0, vulkan1_1, vulkan1_2, vulkan1_3 };

inline constexpr TargetEnv kAllTargetEnvs[] = {TargetEnv::vulkan1_0, TargetEnv::vulkan1_1, TargetEnv::vulkan1_2,
                                               TargetEnv::vulkan1_3};

// "vulkan1.0" ... "vulkan1.3", the names spirv-val's --target-env uses.
std::string_view to_string(TargetEnv env);
std::optional<TargetEnv> parse_target_env(std::string_view name);

// The SPIR-V version a module for `env` declares, as the header's version word: 0x00010000 for 1.0.
std::uint32_t spirv_version_word(TargetEnv env);

} // namespace kdop
