#include "generator/variant_builder.h"

#include "core/embedded_files.h"
#include "core/parallel_for.h"
#include "generator/clip_emitter.h"
#include "generator/compute_shader.h"
#include "generator/glsl_compiler.h"
#include "generator/spirv_tools.h"

#include <fmt/format.h>

#include <algorithm>
#include <mutex>
#include <optional>
#include <stdexcept>

namespace kdop {
namespace {

constexpr std::string_view kComputeTemplate = "shader_templates/rectify.comp.in";
constexpr std::string_view kHlslComputeTemplate = "shader_templates/rectify.hlsl.in";

// The compute shader `language` asks for, around the function in that language.
Result<std::string> compute_shader(const VariantSpec& spec, SourceLanguage language) {
    const bool hlsl = language == SourceLanguage::hlsl;
    const std::string_view origin = hlsl ? kHlslComputeTemplate : kComputeTemplate;
    auto text = find_embedded_file(origin);
    if (!text) return fail(fmt::format("internal error: {} is not embedded", origin));
    return emit_compute_shader(spec, *text, origin, hlsl ? kHlsl : kGlsl);
}

} // namespace

Result<void> compile_into(BuiltVariant& v, std::string_view source, std::string_view file, TargetEnv env,
                          Result<std::vector<std::uint32_t>> compiled, SpirvOptimization optimization) {
    if (!compiled) return std::unexpected(compiled.error());
    if (auto ok = validate_spirv(*compiled, source, file, "glslang output", env); !ok) return ok;
    *compiled = with_literal_local_size(std::move(*compiled));

    Result<std::vector<std::uint32_t>> optimized = std::move(*compiled);
    if (optimization == SpirvOptimization::performance) {
        optimized = optimize_spirv(*optimized, file, env);
        if (!optimized) return std::unexpected(optimized.error());
        if (auto ok = validate_spirv(*optimized, source, file, "optimized module", env); !ok) return ok;
    }

    auto interface = reflect_interface(*optimized);
    if (!interface) return fail(fmt::format("{}: reflection failed: {}", file, interface.error().message));
    v.interface = std::move(*interface);

    auto shipped = shipped_spirv(*optimized, file, env, v.spec.strip_names);
    if (!shipped) return std::unexpected(shipped.error());
    if (auto ok = validate_spirv(*shipped, source, file, "shipped module", env); !ok) return ok;
    v.spirv = std::move(*shipped);
    v.counts = count_spirv(v.spirv);
    return {};
}

const std::string& BuiltVariant::function(const Dialect& dialect) const {
    for (std::size_t i = 0; i < functions.size(); ++i)
        if (kShaderLanguages[i].dialect == &dialect) return functions[i];
    throw std::logic_error("BuiltVariant::function: a dialect that is not in kShaderLanguages");
}

Result<BuiltVariant> build_variant(const VariantSpec& spec, SourceLanguage language) {
    BuiltVariant v;
    v.spec = spec;
    v.name = variant_name(spec);
    const bool hlsl = language == SourceLanguage::hlsl;
    const std::string file = v.name + (hlsl ? ".hlsl (compute)" : ".comp");
    const TargetEnv env = spec.target_env;

    for (const ShaderLanguage& l : kShaderLanguages) v.functions.push_back(emit_function(spec, *l.dialect));
    auto compute = compute_shader(spec, language);
    if (!compute) return std::unexpected(compute.error());
    (hlsl ? v.compute_hlsl : v.compute_glsl) = std::move(*compute);
    const std::string& source = hlsl ? v.compute_hlsl : v.compute_glsl;

    auto compiled = hlsl ? compile_hlsl_compute(source, file, env) : compile_glsl_compute(source, file, env);
    if (auto ok = compile_into(v, source, file, env, std::move(compiled)); !ok) return std::unexpected(ok.error());
    if (v.counts.loop_merges)
        return fail(fmt::format("{}: {} loop(s) left in the optimized SPIR-V; variants must be fully unrolled", file,
                                v.counts.loop_merges));
    return v;
}

Result<std::vector<BuiltVariant>> build_variants(std::span<const VariantSpec> specs, unsigned threads,
                                                 const BuildProgress& progress, SourceLanguage language) {
    std::vector<std::optional<Result<BuiltVariant>>> results(specs.size());
    std::size_t done = 0;
    std::mutex progress_mutex;
    parallel_for(specs.size(), threads, [&](std::size_t i) {
        results[i] = build_variant(specs[i], language);
        std::lock_guard lock(progress_mutex);
        ++done;
        if (progress) progress(done, specs.size(), variant_name(specs[i]));
    });

    std::vector<BuiltVariant> built;
    std::string errors;
    for (auto& result : results) {
        if (*result)
            built.push_back(std::move(**result));
        else
            errors += result->error().message + (result->error().message.ends_with('\n') ? "" : "\n");
    }
    if (!errors.empty()) return fail(errors);
    return built;
}

} // namespace kdop
