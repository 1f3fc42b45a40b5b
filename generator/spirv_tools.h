// The SPIRV-Tools stages of a variant's build: validate what glslang produced, optimize it for
// performance, validate again, strip debug information. Messages name the GLSL line where the
// module's OpLine information allows it.
#pragma once

#include "result.h"
#include "target_env.h"

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

// Drops OpSource, OpString, OpLine and OpName: the shipped module carries code only, so its bytes
// do not depend on file names or comments.
Result<std::vector<std::uint32_t>> strip_debug_info(const std::vector<std::uint32_t>& words, std::string_view name,
                                                    TargetEnv env = TargetEnv::vulkan1_0);

} // namespace kdop
