// Clip emission: a pure function from a VariantSpec to the clip function's text, in GLSL or the same
// function in HLSL or WGSL (shader_dialect.h). No loops and no arrays indexed at
// run time are emitted; every slab is written out. Per axis, a zero component emits nothing and
// a +-1 component is added or subtracted without a multiply: each axis is first scaled so its
// largest component is exactly +1 (scaled_axis.h), which also moves one multiply per projection
// out of every dot product.
//
// The projection writer (project) and the two slab writers are the places to change when the cost
// bench finds a cheaper written form; EmitStyle (variant_spec.h) selects among the forms written so far.
#pragma once

#include "generator/shader_dialect.h"
#include "generator/variant_spec.h"

#include <string>

namespace kdop {

// "dop16-grass-clip-n9" -> "kdop_dop16_grass_clip_n9": the function name of a variant, the same in
// every language.
std::string glsl_function_name(const VariantSpec& spec);

// The includable function of a variant in GLSL, HLSL or WGSL, with a header saying where it came
// from and (GLSL, HLSL) an include guard, ready to paste or #include into a TAA shader. Signatures:
//   vec3 kdop_<set>_clip_<n>(vec3 current, vec3 history, vec3 neighborhood[N])
//   vec3 kdop_<set>_varclip_<n>(vec3 current, vec3 history, float gamma, vec3 neighborhood[N])
// in HLSL the same with float3, in WGSL
//   fn kdop_<set>_clip_<n>(current: vec3f, history: vec3f, neighborhood: array<vec3f, N>) -> vec3f
// with `gamma: f32` before the neighborhood for varclip. All write the same operations in the same order.
std::string emit_function(const VariantSpec& spec, const Dialect& dialect = kGlsl);

} // namespace kdop
