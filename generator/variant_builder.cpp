#include "variant_builder.h"

#include "embedded_files.h"
#include "glsl_compiler.h"
#include "glsl_emitter.h"
#include "spirv_tools.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <optional>
#include <thread>

namespace kdop {
namespace {

constexpr std::string_view kComputeTemplate = "shader_templates/rectify.comp.in";

} // namespace

Result<void> compile_into(BuiltVariant& v, std::string_view file, Result<std::vector<std::uint32_t>> compiled) {
    if (!compiled) return std::unexpected(compiled.error());
    if (auto ok = validate_spirv(*compiled, v.compute_glsl, file, "glslang output"); !ok) return ok;

    auto optimized = optimize_spirv(*compiled, file);
    if (!optimized) return std::unexpected(optimized.error());
    if (auto ok = validate_spirv(*optimized, v.compute_glsl, file, "optimized module"); !ok) return ok;

    auto interface = reflect_compute_interface(*optimized);
    if (!interface) return fail(fmt::format("{}: reflection failed: {}", file, interface.error().message));
    v.interface = std::move(*interface);

    auto stripped = strip_debug_info(*optimized, file);
    if (!stripped) return std::unexpected(stripped.error());
    if (auto ok = validate_spirv(*stripped, v.compute_glsl, file, "shipped module"); !ok) return ok;
    v.spirv = std::move(*stripped);
    v.counts = count_spirv(v.spirv);
    return {};
}

Result<BuiltVariant> build_variant(const VariantSpec& spec) {
    BuiltVariant v;
    v.spec = spec;
    v.name = variant_name(spec);
    const std::string file = v.name + ".comp";

    auto compute_template = find_embedded_file(kComputeTemplate);
    if (!compute_template) return fail(fmt::format("internal error: {} is not embedded", kComputeTemplate));
    v.function_glsl = emit_function(spec);
    auto compute = emit_compute_shader(spec, *compute_template, kComputeTemplate);
    if (!compute) return std::unexpected(compute.error());
    v.compute_glsl = std::move(*compute);

    if (auto ok = compile_into(v, file, compile_glsl_compute(v.compute_glsl, file)); !ok)
        return std::unexpected(ok.error());
    if (v.counts.loop_merges)
        return fail(fmt::format("{}: {} loop(s) left in the optimized SPIR-V; variants must be fully unrolled", file,
                                v.counts.loop_merges));
    return v;
}

Result<std::vector<BuiltVariant>> build_variants(std::span<const VariantSpec> specs, unsigned threads,
                                                 const BuildProgress& progress) {
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    threads = std::min<unsigned>(threads, static_cast<unsigned>(std::max<std::size_t>(specs.size(), 1)));

    std::vector<std::optional<Result<BuiltVariant>>> results(specs.size());
    std::atomic<std::size_t> next{0};
    std::size_t done = 0;
    std::mutex progress_mutex;
    {
        std::vector<std::jthread> workers;
        for (unsigned t = 0; t < threads; ++t)
            workers.emplace_back([&] {
                for (std::size_t i; (i = next++) < specs.size();) {
                    results[i] = build_variant(specs[i]);
                    std::lock_guard lock(progress_mutex);
                    ++done;
                    if (progress) progress(done, specs.size(), variant_name(specs[i]));
                }
            });
    }

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
