// The SPIRV-Tools stages of a variant's build: validate what glslang produced, optimize it for
// performance, validate again, strip what does not ship. Messages name the GLSL line where the
// module's OpLine information allows it.
#pragma once

#include "core/result.h"
#include "generator/target_env.h"

#include <cstdint>
#include <string_view>
#include <vector>

namespace kdop {

// Validates `words` for `env`. `source` and `name` are the shader it came from, for messages;
// `stage` says which step's output is validated ("glslang output", "optimized module", ...).
Result<void> validate_spirv(const std::vector<std::uint32_t>& words, std::string_view source, std::string_view name,
                            std::string_view stage, TargetEnv env = TargetEnv::vulkan1_0);

// SPIRV-Tools' performance recipe (the passes of `spirv-opt -O`), for `env`.
Result<std::vector<std::uint32_t>> optimize_spirv(const std::vector<std::uint32_t>& words, std::string_view name,
                                                  TargetEnv env = TargetEnv::vulkan1_0);

// The module that ships: without the line information kdop's compilation adds for its messages
// (spirv_module.h's without_line_info), so its bytes do not depend on file names or comments.
// Names stay, as glslc keeps them, so that spirv-cross output, RenderDoc and validation messages
// read with the shader's own names; with `strip_names`, every debug instruction goes (SPIRV-Tools'
// strip-debug pass), for shipping.
Result<std::vector<std::uint32_t>> shipped_spirv(const std::vector<std::uint32_t>& words, std::string_view name,
                                                 TargetEnv env, bool strip_names);

} // namespace kdop
