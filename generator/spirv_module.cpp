#include "generator/spirv_module.h"

#include <spirv/unified1/spirv.hpp>

#include <map>

namespace kdop {
namespace {

constexpr std::size_t kHeaderWords = 5;

} // namespace

std::vector<SpirvInstruction> spirv_instructions(std::span<const std::uint32_t> words) {
    // The physical layout is simple (each instruction's first word holds its length and opcode),
    // so a direct walk is shorter and clearer than spvBinaryParse's callback interface.
    std::vector<SpirvInstruction> instructions;
    if (words.size() < kHeaderWords || words[0] != spv::MagicNumber) return instructions;
    for (std::size_t i = kHeaderWords; i < words.size();) {
        std::uint32_t length = words[i] >> spv::WordCountShift;
        if (length == 0 || i + length > words.size()) return {};
        instructions.push_back({words[i] & spv::OpCodeMask, words.subspan(i + 1, length - 1), instructions.size() + 1});
        i += length;
    }
    return instructions;
}

SpirvCounts count_spirv(std::span<const std::uint32_t> words) {
    SpirvCounts counts{};
    bool in_function = false;
    for (const SpirvInstruction& inst : spirv_instructions(words)) {
        ++counts.instructions;
        if (inst.opcode == spv::OpFunction) in_function = true;
        if (in_function) ++counts.function_instructions;
        if (inst.opcode == spv::OpFunctionEnd) in_function = false;
        if (inst.opcode == spv::OpLoopMerge) ++counts.loop_merges;
    }
    return counts;
}

std::uint64_t spirv_hash(std::span<const std::uint32_t> words) {
    std::uint64_t hash = 0xcbf29ce484222325ull;
    for (std::uint32_t w : words)
        for (int b = 0; b < 4; ++b) {
            hash ^= (w >> (8 * b)) & 0xff;
            hash *= 0x100000001b3ull;
        }
    return hash;
}

std::vector<std::uint32_t> with_literal_local_size(std::vector<std::uint32_t> words) {
    std::map<std::uint32_t, std::uint32_t> constants; // OpConstant's result id -> its 32-bit value
    std::vector<std::size_t> modes;                   // word offsets of OpExecutionModeId LocalSizeId
    for (std::size_t i = kHeaderWords; i < words.size() && words[0] == spv::MagicNumber;) {
        const std::uint32_t length = words[i] >> spv::WordCountShift, opcode = words[i] & spv::OpCodeMask;
        if (length == 0 || i + length > words.size()) return words; // not a module; validation says so
        if (opcode == spv::OpConstant && length == 4) constants[words[i + 2]] = words[i + 3];
        if (opcode == spv::OpExecutionModeId && length == 6 && words[i + 2] == spv::ExecutionModeLocalSizeId)
            modes.push_back(i);
        i += length;
    }
    for (std::size_t i : modes) {
        const auto x = constants.find(words[i + 3]), y = constants.find(words[i + 4]), z = constants.find(words[i + 5]);
        if (x == constants.end() || y == constants.end() || z == constants.end()) continue;
        // The same length: OpExecutionMode <entry> LocalSize x y z.
        words[i] = (6u << spv::WordCountShift) | spv::OpExecutionMode;
        words[i + 2] = spv::ExecutionModeLocalSize;
        words[i + 3] = x->second;
        words[i + 4] = y->second;
        words[i + 5] = z->second;
    }
    return words;
}

std::vector<std::uint32_t> without_line_info(std::span<const std::uint32_t> words) {
    if (words.size() < kHeaderWords) return {words.begin(), words.end()};
    std::vector<std::uint32_t> out(words.begin(), words.begin() + kHeaderWords);
    for (const SpirvInstruction& inst : spirv_instructions(words)) {
        switch (inst.opcode) {
        case spv::OpLine:
        case spv::OpNoLine:
        case spv::OpString:
        case spv::OpSourceContinued:
        case spv::OpModuleProcessed: continue;
        case spv::OpSource: // language and version only
            out.push_back((3u << spv::WordCountShift) | spv::OpSource);
            out.insert(out.end(), inst.operands.begin(), inst.operands.begin() + 2);
            continue;
        default:
            out.push_back((static_cast<std::uint32_t>(inst.operands.size() + 1) << spv::WordCountShift) | inst.opcode);
            out.insert(out.end(), inst.operands.begin(), inst.operands.end());
        }
    }
    return out;
}

int glsl_line_of_instruction(std::span<const std::uint32_t> words, std::size_t ordinal) {
    int line = 0;
    for (const SpirvInstruction& inst : spirv_instructions(words)) {
        if (inst.ordinal > ordinal) break;
        if (inst.opcode == spv::OpLine) line = static_cast<int>(inst.operands[1]);
        if (inst.opcode == spv::OpNoLine) line = 0;
    }
    return line;
}

} // namespace kdop
