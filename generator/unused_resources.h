// What a shader declares but its SPIR-V does not have, and the warning kdop-gen gives for each. A
// resource the entry point never uses is not in the SPIR-V, so not in the reflection either: the
// registry and the JSON list no binding for it, and engine code that looks it up by name finds
// nothing. Said, not left for the engine to find: the HLSL port of a GLSL resolve that reads its
// current frame with Load has no use for the sampler GLSL's texelFetch needed, and the two tables
// differed without a word.
#pragma once

#include "generator/declared_resources.h"
#include "generator/shader_reflection.h"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

// Those of `declared` that `reflected` lacks: a descriptor by its name (both name resources by one
// rule), the push-constant block when `reflected` has no push constants.
std::vector<DeclaredResource> unused_resources(std::span<const DeclaredResource> declared,
                                               const ShaderInterface& reflected);

// "<file>: warning: sampler 'nearest_sampler' (set 0, binding 1) is not used by the entry point
// 'main', ...", one line.
std::string unused_resource_warning(std::string_view file, std::string_view entry_point,
                                    const DeclaredResource& resource);

} // namespace kdop
