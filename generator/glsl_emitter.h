// Shader emission: a pure function from a VariantSpec to shader text, in GLSL or the same function
// in HLSL or WGSL (shader_dialect.h). No loops and no arrays indexed at
// run time are emitted; every slab is written out. Per axis, a zero component emits nothing and
// a +-1 component is added or subtracted without a multiply: each axis is first scaled so its
// largest component is exactly +1 (see ScaledAxis), which also moves one multiply per projection
// out of every dot product.
//
// The projection writer (project) and the two slab writers are the places to change when the cost
// bench finds a cheaper written form; EmitStyle (variant_spec.h) selects among the forms written so far.
#pragma once

#include "result.h"
#include "shader_dialect.h"
#include "variant_spec.h"

#include <glm/vec3.hpp>

#include <string>
#include <string_view>

namespace kdop {

// Slab dilation of the paper (Sec. 3): 1e-5 per unit of axis length.
inline constexpr double kSlabPadding = 1e-5;

// An axis rescaled for emission. Clipping does not change when an axis is multiplied by any
// nonzero factor: a positive one scales slab, projection and ray alike, and a negative one swaps
// the slab's min and max. So each axis is multiplied by 1 / (its largest-magnitude component),
// which makes that component exactly +1.
struct ScaledAxis {
    glm::vec3 coefficients; // rounded to float once; the largest is exactly 1
    double factor;          // file axis x factor = coefficients
    float padding;          // kSlabPadding in the units of the scaled axis
};

ScaledAxis scale_axis(const glm::dvec3& axis);

// Where a hardened clip measures its slabs from. Absolute: the colors as they are, minus the current
// color's projection once per slab. Relative: the colors minus the current color, three subtracts
// per neighbor once, after which the origin is 0 and every slab is cheaper. The generator takes
// the cheaper for the set (hardened_frame in analytic_cost.h: relative for the k-DOPs, absolute for
// the AABBs in n9); the variance clip is always relative, as its moments need.
enum class Frame { absolute, relative };

// "dop16-grass-clip-n9" -> "kdop_dop16_grass_clip_n9": the GLSL function name of a variant.
std::string glsl_function_name(const VariantSpec& spec);

// The includable function of a variant in GLSL, HLSL or WGSL, with a header saying where it came
// from and (GLSL, HLSL) an include guard, ready to paste or #include into a TAA shader. Signatures:
//   vec3 kdop_<set>_clip_<n>(vec3 current, vec3 history, vec3 neighborhood[N])
//   vec3 kdop_<set>_varclip_<n>(vec3 current, vec3 history, float gamma, vec3 neighborhood[N])
// in HLSL the same with float3, in WGSL
//   fn kdop_<set>_clip_<n>(current: vec3f, history: vec3f, neighborhood: array<vec3f, N>) -> vec3f
// with `gamma: f32` before the neighborhood for varclip. All write the same operations in the same order.
std::string emit_function(const VariantSpec& spec, const Dialect& dialect = kGlsl);

// The compute shader of a variant: `compute_template` (shader_templates/rectify.comp.in, or
// rectify.hlsl.in for HLSL) with its @PLACEHOLDERS@ filled in. `template_origin` names the template
// in errors.
Result<std::string> emit_compute_shader(const VariantSpec& spec, std::string_view compute_template,
                                        std::string_view template_origin, const Dialect& dialect = kGlsl);

// The command that regenerates a variant, quoted in generated headers.
std::string regenerate_command(const VariantSpec& spec);

} // namespace kdop
