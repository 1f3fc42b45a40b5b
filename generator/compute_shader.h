// A variant's compute shader: a template (shader_templates/rectify.comp.in, or rectify.hlsl.in for
// HLSL) around the clip function (clip_emitter.h), its gather of the neighborhood and its call.
#pragma once

#include "core/result.h"
#include "generator/shader_dialect.h"
#include "generator/variant_spec.h"

#include <string>
#include <string_view>

namespace kdop {

// `compute_template` with its @PLACEHOLDERS@ filled in; `template_origin` names the template in
// errors, and a placeholder without a value is an error naming its line.
Result<std::string> emit_compute_shader(const VariantSpec& spec, std::string_view compute_template,
                                        std::string_view template_origin, const Dialect& dialect = kGlsl);

} // namespace kdop
