// The shading languages a variant's function is written in: GLSL; HLSL for engines whose shaders
// are HLSL (Unity, Unreal); WGSL for WebGPU renderers and Bevy. The emitter writes the same
// operations in the same order in all three; only the spellings below differ: fma/mad,
// floatBitsToInt/asint/bitcast<i32>, vec3/float3/vec3f, declarations (`float t = 1.0;` /
// `var t: f32 = 1.0;`), the conditional (`c ? a : b` / `select(b, a, c)`), how a scalar is
// broadcast and an array initialized. Min, max, abs, sqrt, dot, clamp and the operators are spelled
// alike; glslang maps each GLSL/HLSL pair to the same SPIR-V instruction (mad and fma to
// GLSL.std.450 Fma), and WGSL's are the same built-ins (Tint writes them as the same instructions).
#pragma once

#include <fmt/format.h>

#include <string>
#include <string_view>

namespace kdop {

struct Dialect {
    std::string_view language;          // "GLSL", "HLSL", "WGSL": the include guard's suffix
    std::string_view vector_prefix;     // "vec", "float", "vec": vec3 / float3 / vec3f
    std::string_view vector_suffix;     // "", "", "f"
    std::string_view int_vector_prefix; // "ivec", "int", "vec": ivec2 / int2 / vec2i
    std::string_view int_vector_suffix; // "", "", "i"
    std::string_view fma;               // fma / mad / fma
    std::string_view float_bits_to_int; // floatBitsToInt / asint / bitcast<i32>
    std::string_view unroll;            // the loop attribute asking for full unrolling (WGSL has none)
    std::string_view unroll_note;       // what the loop form needs for it, for the header comment
    std::string_view loop_extension;    // what the loop-form function enables for it (GLSL), or nothing
    // FLT_MAX. WGSL refuses a literal beyond it (3.40282347e38 rounds to it in GLSL and HLSL), so
    // there it is written exactly.
    std::string_view float_max;

    bool wgsl() const { return language == "WGSL"; }
    std::string_view scalar() const { return wgsl() ? "f32" : "float"; }
    // "vec3" / "float3" / "vec3f".
    std::string vec(int size) const { return fmt::format("{}{}{}", vector_prefix, size, vector_suffix); }
    std::string ivec(int size) const { return fmt::format("{}{}{}", int_vector_prefix, size, int_vector_suffix); }
    // The dialect's spelling of "float", "vec2", "vec3" or "bool".
    std::string type(std::string_view glsl_type) const {
        if (glsl_type == "float") return std::string(scalar());
        if (glsl_type == "vec2") return vec(2);
        if (glsl_type == "vec3") return vec(3);
        return std::string(glsl_type);
    }
    // A local of `glsl_type`: `float t` / `var t: f32`, or in WGSL `let t: f32` when it is never
    // assigned again.
    std::string declare(std::string_view glsl_type, std::string_view name, bool assigned_again = false) const {
        if (!wgsl()) return fmt::format("{} {}", type(glsl_type), name);
        return fmt::format("{} {}: {}", assigned_again ? "var" : "let", name, type(glsl_type));
    }
    // `condition ? if_true : if_false`, in WGSL select(if_false, if_true, condition). Both are one
    // select of already computed values (the emitter's operands have no side effects).
    std::string select(std::string_view condition, std::string_view if_true, std::string_view if_false) const {
        return wgsl() ? fmt::format("select({}, {}, {})", if_false, if_true, condition)
                      : fmt::format("{} ? {} : {}", condition, if_true, if_false);
    }
    // A scalar broadcast to a vector: vec3(x) in GLSL and WGSL; HLSL has no one-argument vector
    // constructor, so a cast, (float3)x, which HLSL defines as the broadcast.
    std::string splat(int size, std::string_view scalar_value) const {
        return language == "HLSL" ? fmt::format("({}){}", vec(size), scalar_value)
                                  : fmt::format("{}({})", vec(size), scalar_value);
    }
    // The opening and closing of an array's initializer: vec3[]( ... ) / { ... } / array<vec3f, N>( ... ).
    std::string array_open(int element_size, int count) const {
        if (wgsl()) return fmt::format("array<{}, {}>(", vec(element_size), count);
        return language == "GLSL" ? vec(element_size) + "[](" : "{";
    }
    std::string_view array_close() const { return language == "HLSL" ? "}" : ")"; }
};

inline constexpr Dialect kGlsl{
    .language = "GLSL",
    .vector_prefix = "vec",
    .vector_suffix = "",
    .int_vector_prefix = "ivec",
    .int_vector_suffix = "",
    .fma = "fma",
    .float_bits_to_int = "floatBitsToInt",
    .unroll = "[[unroll]] ",
    .unroll_note = "it enables GL_EXT_control_flow_attributes, which [[unroll]] needs",
    // In the function itself, so that it compiles wherever it is included (glslang takes an
    // #extension after other code in desktop GLSL).
    .loop_extension = "#extension GL_EXT_control_flow_attributes : enable\n",
    .float_max = "3.40282347e38",
};

inline constexpr Dialect kHlsl{
    .language = "HLSL",
    .vector_prefix = "float",
    .vector_suffix = "",
    .int_vector_prefix = "int",
    .int_vector_suffix = "",
    .fma = "mad",
    .float_bits_to_int = "asint",
    .unroll = "[unroll] ",
    .unroll_note = "its loops carry [unroll]",
    .loop_extension = "", // HLSL's [unroll] needs none
    .float_max = "3.40282347e38",
};

inline constexpr Dialect kWgsl{
    .language = "WGSL",
    .vector_prefix = "vec",
    .vector_suffix = "f",
    .int_vector_prefix = "vec",
    .int_vector_suffix = "i",
    .fma = "fma",
    .float_bits_to_int = "bitcast<i32>",
    .unroll = "",
    .unroll_note = "WGSL has no unroll attribute: the compiler decides",
    .loop_extension = "",
    .float_max = "3.4028234663852886e38",
};

// A language a variant's function is written in: the extension of its file (".glsl") and how it is
// spelled.
struct ShaderLanguage {
    std::string_view extension;
    const Dialect* dialect;
};

// Every one, from the one list (generator/shader_languages.def).
inline constexpr ShaderLanguage kShaderLanguages[] = {
#define KDOP_SHADER_LANGUAGE(extension, dialect) {"." #extension, &dialect},
#include "generator/shader_languages.def"
#undef KDOP_SHADER_LANGUAGE
};

// The language `dialect` is written in (one of kShaderLanguages'), its extension with it.
constexpr const ShaderLanguage& shader_language(const Dialect& dialect) {
    for (const ShaderLanguage& language : kShaderLanguages)
        if (language.dialect == &dialect) return language;
    return kShaderLanguages[0]; // unreachable: every dialect is listed
}

} // namespace kdop
