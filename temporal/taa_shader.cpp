#include "temporal/taa_shader.h"

#include "core/embedded_files.h"
#include "generator/clip_emitter.h"
#include "generator/glsl_compiler.h"
#include "generator/project_shader.h"
#include "generator/variant_builder.h"

#include <fmt/format.h>

namespace kdop {
namespace {

constexpr std::string_view kTemplate = "shader_templates/taa_resolve.comp.in";

} // namespace

std::string resolve_option_defines(const ResolveOptions& o) {
    const int map = o.color_map.kind == ColorMap::Kind::power ? 1 : o.color_map.kind == ColorMap::Kind::log ? 2 : 0;
    // The exponent as the float the CPU's map_color uses, with every digit a float has, so the
    // shader's constant is that value (the option's own digits would be rounded twice).
    return fmt::format("#define KDOP_HISTORY_FILTER {}\n#define KDOP_COLOR_MAP {}\n#define KDOP_MAP_EXPONENT {:.9g}\n"
                       "#define KDOP_MAP_LOG_OFFSET {:.9g}\n#define KDOP_DILATE_MOTION {}\n"
                       "#define KDOP_DEPTH_NEARER_LARGER {}\n#define KDOP_UPSCALE {}\n#define KDOP_UPSCALE_FILTER {}\n"
                       "#define KDOP_SAMPLE_DISTANCE {}\n#define KDOP_NO_HISTORY {}\n",
                       o.history_filter == HistoryFilter::catmull_rom ? 1 : 0, map, float(o.color_map.exponent),
                       kColorMapLogOffset, o.dilate_motion ? 1 : 0, o.depth_nearer_larger ? 1 : 0, o.upscale ? 1 : 0,
                       o.upscale_filter == UpscaleFilter::gaussian ? 1 : 0,
                       o.sample_distance.kind != SampleDistance::Kind::all ? 1 : 0, o.no_history ? 1 : 0);
}

Result<std::unique_ptr<RunnableVariant>> build_taa_shader(std::string_view rectification, const std::string& name,
                                                          const ResolveOptions& options) {
    auto source = find_embedded_file(kTemplate);
    if (!source) return fail(fmt::format("internal error: {} is not embedded", kTemplate));
    BuiltVariant built;
    built.spec.mode = Mode::shader;
    built.name = name;
    built.compute_glsl = std::string(*source);
    const std::string file = name + ".comp";
    const std::string defines = resolve_option_defines(options);
    IncludeResolver resolve = [&](std::string_view header, std::string_view) -> std::optional<IncludedSource> {
        // The one include a renderer's own resolve has too (build_own_resolve): the template is one.
        if (header == "kdop_variant.glsl")
            return IncludedSource{name + "/kdop_variant.glsl", std::string(rectification)};
        if (header == "resolve_options.glsl") return IncludedSource{name + "/resolve_options.glsl", defines};
        return std::nullopt;
    };
    auto compiled = compile_glsl_compute(built.compute_glsl, file, TargetEnv::vulkan1_0, resolve);
    if (auto ok = compile_into(built, built.compute_glsl, file, TargetEnv::vulkan1_0, std::move(compiled)); !ok)
        return std::unexpected(ok.error());
    return std::make_unique<RunnableVariant>(std::move(built));
}

std::string kdop_variant_source(const VariantSpec& spec, bool hlsl) {
    const int count = spec.neighborhood == Neighborhood::n9 ? 9 : 5;
    const std::string gamma = spec.mode == Mode::varclip ? "gamma, " : "";
    const char* vec3 = hlsl ? "float3" : "vec3";
    return fmt::format("#define KDOP_NEIGHBORS {0}\n{1}\n"
                       "{4} kdop_rectify({4} current, {4} history, float gamma, {4} neighborhood[{0}])\n"
                       "{{\n    return {2}(current, history, {3}neighborhood);\n}}\n",
                       count, emit_function(spec, hlsl ? kHlsl : kGlsl), glsl_function_name(spec), gamma, vec3);
}

Result<std::unique_ptr<RunnableVariant>> build_taa_shader(const VariantSpec& spec, const ResolveOptions& options) {
    if (spec.mode != Mode::clip && spec.mode != Mode::varclip)
        return fail(fmt::format("{}: the TAA resolve takes clip and varclip variants", variant_name(spec)));
    // The variant's function as a renderer includes it, and the one signature the resolve calls.
    return build_taa_shader(kdop_variant_source(spec, false), "taa-" + variant_name(spec), options);
}

Result<std::unique_ptr<RunnableVariant>> build_own_resolve(const std::filesystem::path& shader, const VariantSpec& spec,
                                                           const std::string& hlsl_entry_point) {
    if (spec.mode != Mode::clip && spec.mode != Mode::varclip)
        return fail(fmt::format("{}: a resolve takes clip and varclip variants", variant_name(spec)));
    auto kind = shader_file_kind(shader);
    if (!kind) return std::unexpected(kind.error());
    if (kind->stage != ShaderStage::compute)
        return fail(fmt::format("{}: a resolve is a compute shader (.comp or .cs.hlsl)", shader.string()));
    const std::string header = kind->hlsl ? "kdop_variant.hlsl" : "kdop_variant.glsl";
    ProjectShaderOptions options;
    options.hlsl_entry_point = hlsl_entry_point;
    options.provided.push_back({header, kdop_variant_source(spec, kind->hlsl)});
    auto built = build_project_shader(shader, {}, options);
    if (!built) return std::unexpected(built.error());
    if (built->provided_included.empty())
        return fail(fmt::format("{}: does not #include \"{}\", so no variant would be measured in it: include it "
                                "and clip with kdop_rectify(current, history, gamma, neighborhood) (docs/taa.md, "
                                "\"Your own resolve\")",
                                shader.string(), header));
    built->built.name = fmt::format("{}-{}", kind->name, variant_name(spec));
    return std::make_unique<RunnableVariant>(std::move(built->built));
}

std::string spatial_upscale_name(UpscaleFilter filter) { return fmt::format("spatial-{}", to_string(filter)); }

Result<std::unique_ptr<RunnableVariant>> build_spatial_upscale_shader(const ResolveOptions& options) {
    if (!options.upscale) return fail("internal error: a spatial-only upscale of a resolve that does not upscale");
    ResolveOptions spatial = options;
    spatial.no_history = true;
    // The resolve writes the filtered current color before it clips: no clip is ever called.
    constexpr std::string_view kNoClip = "#define KDOP_NEIGHBORS 9\n"
                                         "vec3 kdop_rectify(vec3 current, vec3 history, float gamma, vec3 n[9])\n"
                                         "{\n    return current;\n}\n";
    return build_taa_shader(kNoClip, "taa-" + spatial_upscale_name(options.upscale_filter), spatial);
}

} // namespace kdop
