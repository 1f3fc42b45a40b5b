// Static cost of a module: its scalar floating-point operations, counted from the optimized
// SPIR-V the driver receives. Vector operations count once per component, OpDot of an N-vector
// as 2N - 1 (N multiplies, N - 1 adds), Fma as 1, FClamp as 2 (a min and a max). The count is
// deterministic, so it compares written forms exactly where timings are noisy.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace kdop {

struct FloatOps {
    std::size_t mul = 0;            // OpFMul, OpVectorTimesScalar, the multiplies of OpDot
    std::size_t add_sub = 0;        // OpFAdd, OpFSub, OpFNegate, the adds of OpDot
    std::size_t fma = 0;            // GLSL.std.450 Fma
    std::size_t min_max = 0;        // FMin, FMax, NMin, NMax, FClamp (2 each)
    std::size_t div = 0;            // OpFDiv (a reciprocal is one)
    std::size_t compare_select = 0; // ordered/unordered float compares, OpSelect of floats
    std::size_t other = 0;          // sqrt and every other float instruction

    std::size_t total() const { return mul + add_sub + fma + min_max + div + compare_select + other; }
};

// The float operations of every function body in the module (for kdop's shaders: main, after the
// optimizer has inlined everything into it).
FloatOps count_float_ops(std::span<const std::uint32_t> words);

} // namespace kdop
