#include "spirv_module.h"

#include <fmt/format.h>
#include <spirv/unified1/spirv.hpp>

#include <algorithm>
#include <map>
#include <optional>

namespace kdop {
namespace {

constexpr std::size_t kHeaderWords = 5;

// A literal string operand: UTF-8 bytes packed little-endian into words, NUL-terminated.
std::string literal_string(std::span<const std::uint32_t> words) {
    std::string s;
    for (std::uint32_t w : words)
        for (int b = 0; b < 4; ++b) {
            char c = static_cast<char>((w >> (8 * b)) & 0xff);
            if (c == 0) return s;
            s += c;
        }
    return s;
}

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

Result<ShaderInterface> reflect_compute_interface(std::span<const std::uint32_t> words) {
    struct Type {
        std::uint32_t opcode;
        std::vector<std::uint32_t> operands;
    };
    std::map<std::uint32_t, Type> types;
    std::map<std::uint32_t, std::string> names;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::string> member_names;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> member_offsets;
    std::map<std::uint32_t, std::uint32_t> sets, bindings;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> variables; // (pointer type, id)
    std::optional<std::uint32_t> entry_id;
    // glslang writes the workgroup size as LocalSizeId for SPIR-V 1.6 (Vulkan 1.3): ids of constants,
    // declared after the execution mode, so resolved once the module has been read.
    std::array<std::uint32_t, 3> local_size_ids{};
    std::map<std::uint32_t, std::uint32_t> constants;

    ShaderInterface interface;
    for (const SpirvInstruction& inst : spirv_instructions(words)) {
        auto op = inst.operands;
        switch (inst.opcode) {
        case spv::OpEntryPoint:
            if (op[0] != spv::ExecutionModelGLCompute) return fail("module has a non-compute entry point");
            if (entry_id) return fail("module has more than one entry point");
            entry_id = op[1];
            interface.entry_point = literal_string(op.subspan(2));
            break;
        case spv::OpExecutionMode:
            if (op[1] == spv::ExecutionModeLocalSize) interface.local_size = {op[2], op[3], op[4]};
            break;
        case spv::OpExecutionModeId:
            if (op[1] == spv::ExecutionModeLocalSizeId) local_size_ids = {op[2], op[3], op[4]};
            break;
        case spv::OpConstant:
            if (op.size() == 3) constants[op[1]] = op[2]; // 32-bit: the workgroup size's uint
            break;
        case spv::OpName: names[op[0]] = literal_string(op.subspan(1)); break;
        case spv::OpMemberName: member_names[{op[0], op[1]}] = literal_string(op.subspan(2)); break;
        case spv::OpDecorate:
            if (op[1] == spv::DecorationDescriptorSet) sets[op[0]] = op[2];
            if (op[1] == spv::DecorationBinding) bindings[op[0]] = op[2];
            break;
        case spv::OpMemberDecorate:
            if (op[2] == spv::DecorationOffset) member_offsets[{op[0], op[1]}] = op[3];
            break;
        case spv::OpTypeFloat:
        case spv::OpTypeInt:
        case spv::OpTypeVector:
        case spv::OpTypeImage:
        case spv::OpTypeSampledImage:
        case spv::OpTypeStruct:
        case spv::OpTypePointer: types[op[0]] = {inst.opcode, {op.begin() + 1, op.end()}}; break;
        case spv::OpVariable: variables.emplace_back(op[0], op[1]); break;
        default: break;
        }
    }
    if (!entry_id) return fail("module has no entry point");
    if (interface.local_size[0] == 0 && local_size_ids[0] != 0)
        for (int i = 0; i < 3; ++i) {
            auto value = constants.find(local_size_ids[i]);
            if (value == constants.end()) return fail("compute entry point's LocalSizeId is not a constant");
            interface.local_size[i] = value->second;
        }
    if (interface.local_size[0] == 0) return fail("compute entry point has no LocalSize execution mode");

    auto type_size = [&](std::uint32_t id) -> std::optional<std::uint32_t> {
        const Type& t = types[id];
        if (t.opcode == spv::OpTypeFloat || t.opcode == spv::OpTypeInt) return t.operands[0] / 8;
        if (t.opcode == spv::OpTypeVector && types[t.operands[0]].opcode != spv::OpTypeVector)
            return types[t.operands[0]].operands[0] / 8 * t.operands[1];
        return std::nullopt;
    };

    for (auto [pointer_type, id] : variables) {
        const Type& pointer = types[pointer_type];
        std::uint32_t storage = pointer.operands[0];
        const Type& pointee = types[pointer.operands[1]];
        std::string name = names.count(id) ? names[id] : fmt::format("%{}", id);
        if (storage == spv::StorageClassUniformConstant) {
            DescriptorType type;
            if (pointee.opcode == spv::OpTypeSampledImage)
                type = DescriptorType::combined_image_sampler;
            else if (pointee.opcode == spv::OpTypeImage && pointee.operands[5] == 2)
                type = DescriptorType::storage_image;
            else
                return fail(fmt::format("resource '{}' has a descriptor type kdop does not reflect", name));
            if (!sets.count(id) || !bindings.count(id))
                return fail(fmt::format("resource '{}' has no descriptor set or binding", name));
            interface.bindings.push_back({sets[id], bindings[id], type, name});
        } else if (storage == spv::StorageClassPushConstant) {
            if (pointee.opcode != spv::OpTypeStruct) return fail("push constant is not a block");
            for (std::uint32_t m = 0; m < pointee.operands.size(); ++m) {
                auto size = type_size(pointee.operands[m]);
                if (!size) return fail("push-constant member is not a scalar or vector");
                std::uint32_t offset = member_offsets[{pointer.operands[1], m}];
                interface.push_constants.push_back({member_names[{pointer.operands[1], m}], offset, *size});
                interface.push_constant_size = std::max(interface.push_constant_size, offset + *size);
            }
        } else if (storage == spv::StorageClassUniform || storage == spv::StorageClassStorageBuffer) {
            return fail(fmt::format("buffer '{}' is not reflected by kdop", name));
        }
    }
    std::sort(interface.bindings.begin(), interface.bindings.end(), [](const BindingInfo& a, const BindingInfo& b) {
        return std::tie(a.set, a.binding) < std::tie(b.set, b.binding);
    });
    return interface;
}

} // namespace kdop
