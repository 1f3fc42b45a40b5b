// The TAA resolve of `kdop taa` (shader_templates/taa_resolve.comp.in) around one rectification:
// the includable function of a clip variant, exactly as kdop generates it for a renderer, or any
// function a test supplies (one that returns the current color, say), and one set of resolve
// options, as compile-time defines. Built in-process like a project's own shader
// (generator/project_shader.h): compiled by glslang, validated, optimized and reflected, loaded by
// the runtime as any variant.
#pragma once

#include "core/result.h"
#include "generator/runnable_variant.h"
#include "generator/variant_spec.h"
#include "temporal/resolve_options.h"

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace kdop {

// The resolve for `spec` (a clip or variance clip), named "taa-<variant>".
Result<std::unique_ptr<RunnableVariant>> build_taa_shader(const VariantSpec& spec, const ResolveOptions& options = {});

// The resolve around `rectification`: GLSL that defines KDOP_NEIGHBORS (9 or 5) and
//   vec3 kdop_rectify(vec3 current, vec3 history, float gamma, vec3 neighborhood[KDOP_NEIGHBORS])
// Messages name `name`.
Result<std::unique_ptr<RunnableVariant>> build_taa_shader(std::string_view rectification, const std::string& name,
                                                          const ResolveOptions& options = {});

// The template's "resolve_options.glsl" for `options`: its defines. Beside a copy of the template,
// it makes kdop's resolve a renderer's own for kdop taa --resolve (docs/taa.md, "Your own resolve").
std::string resolve_option_defines(const ResolveOptions& options);

// "kdop_variant.glsl" (or, with `hlsl`, ".hlsl") for `spec`: KDOP_NEIGHBORS and the variant's
// function behind the one name every resolve calls,
//   vec3 kdop_rectify(vec3 current, vec3 history, float gamma, vec3 neighborhood[KDOP_NEIGHBORS])
// (float3 in HLSL; gamma is passed on to a variance clip and ignored by a clip).
std::string kdop_variant_source(const VariantSpec& spec, bool hlsl);

// A renderer's own resolve around `spec` (kdop taa --resolve): `shader`, a compute shader in GLSL
// (.comp) or HLSL (.cs.hlsl, entry `hlsl_entry_point`), includes "kdop_variant.glsl" (or .hlsl),
// and its other includes resolve as kdop_add_variants resolves a project's (generator/
// project_shader.h). Named "<shader>-<variant>". Refused: a shader that does not include it, or
// does not compile (file:line).
Result<std::unique_ptr<RunnableVariant>> build_own_resolve(const std::filesystem::path& shader, const VariantSpec& spec,
                                                           const std::string& hlsl_entry_point = "main");

// The spatial-only upscale (options.upscale): every output the current color the resolve's filter
// reconstructs from the input samples, with no history, named "spatial-<filter>"
// (spatial_upscale_name). What an upscaling resolve is compared with to see what its history buys.
Result<std::unique_ptr<RunnableVariant>> build_spatial_upscale_shader(const ResolveOptions& options);
std::string spatial_upscale_name(UpscaleFilter filter);

} // namespace kdop
