// The resources a shader's source declares, read from glslang's syntax tree before any SPIR-V is
// made. The SPIR-V keeps only those its entry point uses (glslang's HLSL front end leaves the rest
// out; SPIRV-Tools' optimizer removes GLSL's), so the reflection, taken from the SPIR-V, cannot
// say what was declared and dropped; this list can (unused_resources.h compares the two).
#pragma once

#include <kdop/variant.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace glslang {
class TIntermediate;
}

namespace kdop {

struct DeclaredResource {
    // Named as the reflection names it (shader_reflection.h): the variable, or a block without
    // one (GLSL's `uniform Name { ... };`, HLSL's `cbuffer Name`), the block.
    std::string name;
    std::optional<DescriptorType> type;   // none: the push-constant block
    std::optional<std::uint32_t> binding; // as written, where it is
    std::uint32_t set = 0;                // as written; 0, glslang's default, where it is not
};

// Every descriptor and push-constant block `ast` (a linked glslang program's stage) declares, in the
// order declared, of the kinds kdop reflects (acceleration structures, atomic counters and input
// attachments are left out: kdop refuses them where the SPIR-V has them).
std::vector<DeclaredResource> declared_resources(const glslang::TIntermediate& ast);

} // namespace kdop
