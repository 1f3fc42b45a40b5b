// Reading SPIR-V modules: instruction walking, the counts reported in tables, the loop check, the
// content hash, and the line information that does not ship (reflection: shader_reflection.h).
#pragma once

#include "core/result.h"

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

// The module without what kdop's compilation adds for its own messages and glslc does not by
// default: OpLine, OpNoLine, OpString, OpModuleProcessed, and OpSource's file and text (OpSource
// keeps its language and version). Names (OpName, OpMemberName) stay. SPIRV-Tools' strip passes
// take names with the lines, hence this walk.
std::vector<std::uint32_t> without_line_info(std::span<const std::uint32_t> words);

// The module with a workgroup size of constants written as literals: glslang writes it for SPIR-V
// 1.6 (TARGET_ENV vulkan1.3) as OpExecutionModeId LocalSizeId, which needs the maintenance4 feature
// (VUID-RuntimeSpirv-LocalSizeId-06434) that a Vulkan 1.3 device need not have enabled; glslc
// writes OpExecutionMode LocalSize, as this does. A size of specialization constants stays an id.
std::vector<std::uint32_t> with_literal_local_size(std::vector<std::uint32_t> words);

// The GLSL line of the OpLine in effect at the instruction with this ordinal, or 0.
int glsl_line_of_instruction(std::span<const std::uint32_t> words, std::size_t ordinal);

} // namespace kdop
