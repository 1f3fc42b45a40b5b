// The TAA frame shader of `kdop taa` (shader_templates/taa_frame.comp.in) around one
// rectification: the includable function of a clip variant, exactly as kdop generates it for a
// renderer, or any function a test supplies (one that returns the current color, say). Built
// in-process like a project's own shader (generator/project_shader.h): compiled by glslang,
// validated, optimized and reflected, loaded by the runtime as any variant.
#pragma once

#include "result.h"
#include "runnable_variant.h"
#include "variant_spec.h"

#include <memory>
#include <string>
#include <string_view>

namespace kdop {

// The shader for `spec` (a clip or variance clip), named "taa-<variant>".
Result<std::unique_ptr<RunnableVariant>> build_taa_shader(const VariantSpec& spec);

// The shader around `rectification`: GLSL that defines KDOP_NEIGHBORS (9 or 5) and
//   vec3 kdop_rectify(vec3 current, vec3 history, float gamma, vec3 neighborhood[KDOP_NEIGHBORS])
// Messages name `name`.
Result<std::unique_ptr<RunnableVariant>> build_taa_shader(std::string_view rectification, const std::string& name);

} // namespace kdop
