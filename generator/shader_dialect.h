// The shading languages a variant's function is written in: GLSL, and HLSL for engines whose
// shaders are HLSL. The emitter writes the same operations in the same order in both; only the
// names below differ (fma/mad, floatBitsToInt/asint, vec3/float3, how a scalar is broadcast and an
// array initialized). Min, max, abs, sqrt, dot, clamp and the operators are spelled alike, and
// glslang maps each pair to the same SPIR-V instruction (mad and fma to GLSL.std.450 Fma).
#pragma once

#include <fmt/format.h>

#include <string>
#include <string_view>

namespace kdop {

struct Dialect {
    std::string_view language;          // "GLSL", "HLSL": the include guard's suffix
    std::string_view vector_prefix;     // "vec", "float": vec3 / float3
    std::string_view int_vector_prefix; // "ivec", "int": ivec2 / int2
    std::string_view fma;               // fma / mad
    std::string_view float_bits_to_int; // floatBitsToInt / asint
    std::string_view unroll;            // the loop attribute asking for full unrolling
    std::string_view unroll_note;       // what the loop form needs for it, for the header comment
    std::string_view loop_extension;    // what the loop-form function enables for it (GLSL), or nothing

    // "vec3" / "float3".
    std::string vec(int size) const { return fmt::format("{}{}", vector_prefix, size); }
    std::string ivec(int size) const { return fmt::format("{}{}", int_vector_prefix, size); }
    // A scalar broadcast to a vector: vec3(x) in GLSL; HLSL has no one-argument vector constructor,
    // so a cast, (float3)x, which HLSL defines as the broadcast.
    std::string splat(int size, std::string_view scalar) const {
        return language == "GLSL" ? fmt::format("{}({})", vec(size), scalar) : fmt::format("({}){}", vec(size), scalar);
    }
    // The opening and closing of an array's initializer: vec3[]( ... ) / { ... }.
    std::string array_open(int size) const { return language == "GLSL" ? vec(size) + "[](" : "{"; }
    std::string_view array_close() const { return language == "GLSL" ? ")" : "}"; }
};

inline constexpr Dialect kGlsl{
    .language = "GLSL",
    .vector_prefix = "vec",
    .int_vector_prefix = "ivec",
    .fma = "fma",
    .float_bits_to_int = "floatBitsToInt",
    .unroll = "[[unroll]] ",
    .unroll_note = "it enables GL_EXT_control_flow_attributes, which [[unroll]] needs",
    // In the function itself, so that it compiles wherever it is included (glslang takes an
    // #extension after other code in desktop GLSL).
    .loop_extension = "#extension GL_EXT_control_flow_attributes : enable\n",
};

inline constexpr Dialect kHlsl{
    .language = "HLSL",
    .vector_prefix = "float",
    .int_vector_prefix = "int",
    .fma = "mad",
    .float_bits_to_int = "asint",
    .unroll = "[unroll] ",
    .unroll_note = "its loops carry [unroll]",
};

} // namespace kdop
