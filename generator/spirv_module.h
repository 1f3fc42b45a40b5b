// Reading SPIR-V modules: instruction walking, the counts reported in tables, the loop check, the
// content hash, and reflection of a compute shader's interface (what a caller needs to build its
// pipeline), taken from the module that ships so it cannot drift from it.
#pragma once

#include "result.h"

#include <kdop/variant.h>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace kdop {

struct SpirvInstruction {
    std::uint32_t opcode;
    std::span<const std::uint32_t> operands; // the words after the opcode word
    std::size_t ordinal;                     // 1-based position among the module's instructions
};

// The module's instructions in order; an empty list when the words are not a SPIR-V module.
std::vector<SpirvInstruction> spirv_instructions(std::span<const std::uint32_t> words);

struct SpirvCounts {
    std::size_t instructions;          // every instruction in the module
    std::size_t function_instructions; // instructions inside function bodies: the code a driver compiles
    std::size_t loop_merges;           // OpLoopMerge: nonzero means a loop survived
};
SpirvCounts count_spirv(std::span<const std::uint32_t> words);

// FNV-1a over the module's bytes (little-endian words): a content key for deduplication, not a
// security hash. Written here because 64 bits of FNV are all that is needed.
std::uint64_t spirv_hash(std::span<const std::uint32_t> words);

struct BindingInfo {
    std::uint32_t set;
    std::uint32_t binding;
    DescriptorType type;
    std::string name;
};

struct PushConstantInfo {
    std::string name;
    std::uint32_t offset;
    std::uint32_t size;
};

struct ShaderInterface {
    std::string entry_point;
    std::array<std::uint32_t, 3> local_size{};
    std::vector<BindingInfo> bindings; // sorted by set, then binding
    std::vector<PushConstantInfo> push_constants;
    std::uint32_t push_constant_size = 0;
};

// Reflects a GLCompute module's entry point, workgroup size, descriptor bindings (combined image
// samplers and storage images) and push-constant members. Names come from OpName, so reflect
// before debug information is stripped.
Result<ShaderInterface> reflect_compute_interface(std::span<const std::uint32_t> words);

// The module without what kdop's compilation adds for its own messages and glslc does not by
// default: OpLine, OpNoLine, OpString, OpModuleProcessed, and OpSource's file and text (OpSource
// keeps its language and version). Names (OpName, OpMemberName) stay. SPIRV-Tools' strip passes
// take names with the lines, hence this walk.
std::vector<std::uint32_t> without_line_info(std::span<const std::uint32_t> words);

// The GLSL line of the OpLine in effect at the instruction with this ordinal, or 0.
int glsl_line_of_instruction(std::span<const std::uint32_t> words, std::size_t ordinal);

} // namespace kdop
