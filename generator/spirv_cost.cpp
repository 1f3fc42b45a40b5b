#include "generator/spirv_cost.h"

#include "generator/spirv_module.h"

#include <spirv/unified1/GLSL.std.450.h>
#define SPV_ENABLE_UTILITY_CODE // spv::HasResultAndType
#include <spirv/unified1/spirv.hpp>

#include <map>

namespace kdop {

FloatOps count_float_ops(std::span<const std::uint32_t> words) {
    // Component count of every float scalar or vector type, and the type of every float result.
    std::map<std::uint32_t, std::uint32_t> float_width; // type id -> components
    std::map<std::uint32_t, std::uint32_t> result_type; // result id -> type id
    std::uint32_t glsl_std = 0;
    FloatOps ops;
    bool in_function = false;
    for (const SpirvInstruction& inst : spirv_instructions(words)) {
        auto op = inst.operands;
        switch (inst.opcode) {
        case spv::OpTypeFloat: float_width[op[0]] = 1; continue;
        case spv::OpTypeVector:
            if (float_width.count(op[1])) float_width[op[0]] = op[2];
            continue;
        case spv::OpExtInstImport:
            if (std::string_view(reinterpret_cast<const char*>(op.data() + 1)) == "GLSL.std.450") glsl_std = op[0];
            continue;
        case spv::OpFunction: in_function = true; continue;
        case spv::OpFunctionEnd: in_function = false; continue;
        default: break;
        }
        bool has_result = false, has_type = false;
        spv::HasResultAndType(static_cast<spv::Op>(inst.opcode), &has_result, &has_type);
        if (!in_function || !has_type) continue;
        result_type[op[1]] = op[0];
        auto found = float_width.find(op[0]);
        const bool float_result = found != float_width.end();
        const std::uint32_t n = float_result ? found->second : 0;
        switch (inst.opcode) {
        case spv::OpFMul:
        case spv::OpVectorTimesScalar: ops.mul += n; break;
        case spv::OpFAdd:
        case spv::OpFSub:
        case spv::OpFNegate: ops.add_sub += n; break;
        case spv::OpFDiv: ops.div += n; break;
        case spv::OpDot: {
            std::uint32_t length = float_width[result_type[op[2]]];
            ops.mul += length;
            ops.add_sub += length - 1;
            break;
        }
        case spv::OpSelect:
            if (float_result) ops.compare_select += n;
            break;
        case spv::OpExtInst:
            if (!float_result || op[2] != glsl_std) break;
            switch (op[3]) {
            case GLSLstd450Fma: ops.fma += n; break;
            case GLSLstd450FMin:
            case GLSLstd450FMax:
            case GLSLstd450NMin:
            case GLSLstd450NMax: ops.min_max += n; break;
            case GLSLstd450FClamp:
            case GLSLstd450NClamp: ops.min_max += 2 * n; break;
            default: ops.other += n; break;
            }
            break;
        default:
            // Float compares produce booleans: count them by their operand type.
            if (inst.opcode >= spv::OpFOrdEqual && inst.opcode <= spv::OpFUnordGreaterThanEqual) {
                auto operand = float_width.find(result_type[op[2]]);
                if (operand != float_width.end()) ops.compare_select += operand->second;
            }
            break;
        }
    }
    return ops;
}

} // namespace kdop
