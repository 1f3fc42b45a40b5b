// Building variants: emit GLSL (and the same function in HLSL), compile with glslang, validate,
// optimize, validate again, reflect the interface, drop the line information (and names, if asked), validate what
// ships, and check that no loop survived. All for the spec's target environment (target_env.h). Variants build in
// parallel; results come back in the order of the specs, so output does not depend on thread timing.
#pragma once

#include "core/result.h"
#include "generator/declared_resources.h"
#include "generator/shader_dialect.h"
#include "generator/shader_reflection.h"
#include "generator/spirv_module.h"
#include "generator/variant_spec.h"

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

struct BuiltVariant {
    VariantSpec spec;
    std::string name;
    std::vector<std::string> functions; // the includable function in each of kShaderLanguages, in order
    std::string compute_glsl;           // the compute shader (.comp), when built from GLSL; a SHADERS source
    std::string compute_hlsl;           // the HLSL compute shader, when built from HLSL
    std::vector<std::uint32_t> spirv;   // optimized, validated, as shipped (.spv), from the compute shader
    ShaderInterface interface;
    // A project shader's resources that its source declares and `spirv` lacks, unused by the entry
    // point (unused_resources.h); empty for a variant.
    std::vector<DeclaredResource> unused_resources;
    SpirvCounts counts;

    // The includable function in `dialect` (one of kShaderLanguages').
    const std::string& function(const Dialect& dialect) const;
};

// Which compute shader a build compiles: the GLSL one, which is what ships, or the HLSL one
// (shader_templates/rectify.hlsl.in around the HLSL function, same interface), through glslang's
// HLSL front end, which the tests run to show the HLSL function computes what the GLSL one does.
enum class SourceLanguage { glsl, hlsl };

Result<BuiltVariant> build_variant(const VariantSpec& spec, SourceLanguage language = SourceLanguage::glsl);

// The stages after glslang, shared by variants and a project's own shaders, for `env`: validate
// `compiled`, optimize, validate, reflect into v.interface, drop what does not ship (v.spec.strip_names), validate what
// ships into v.spirv, count. Messages name `file` and the lines of `source`, the shader `compiled` came from.
// SpirvOptimization::none skips SPIRV-Tools' optimizer (every other stage still runs), for shaders
// that are already written unrolled and whose size makes the optimizer take seconds for nothing the
// driver's compiler would not do: the FLIP passes (flip/device_flip.cpp).
enum class SpirvOptimization { performance, none };
Result<void> compile_into(BuiltVariant& v, std::string_view source, std::string_view file, TargetEnv env,
                          Result<std::vector<std::uint32_t>> compiled,
                          SpirvOptimization optimization = SpirvOptimization::performance);

// Called after each variant finishes, from the worker that built it (calls are serialized).
using BuildProgress = std::function<void(std::size_t done, std::size_t total, const std::string& name)>;

// Builds every spec, on up to `threads` threads (0: one per core). Fails if any variant fails,
// with every failing variant's messages in spec order.
Result<std::vector<BuiltVariant>> build_variants(std::span<const VariantSpec> specs, unsigned threads = 0,
                                                 const BuildProgress& progress = {},
                                                 SourceLanguage language = SourceLanguage::glsl);

} // namespace kdop
