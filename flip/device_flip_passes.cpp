#include "flip/device_flip_passes.h"

#include "core/embedded_files.h"
#include "flip/color_spaces.h"
#include "flip/hdr_flip.h"
#include "generator/glsl_compiler.h"
#include "generator/runnable_variant.h"
#include "generator/variant_builder.h"

#include <fmt/format.h>

#include <algorithm>
#include <numbers>
#include <string>

namespace kdop {
namespace {

constexpr std::string_view kTemplate = "shader_templates/flip.comp.in";

// A float as a GLSL literal that reads back as the same float (nine significant digits), always
// with a point or an exponent so GLSL takes it as a float.
std::string literal(float v) {
    std::string s = fmt::format("{:.9g}", v);
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
}

// weights[0..radius], padded with zeros to `length` so that every offset the unrolled loop
// names exists (the zeros are never reached: each kernel's taps stop at its radius).
std::string weights(const char* name, const std::vector<float>& k, int length) {
    std::string s = fmt::format("const float {}[{}] = float[](", name, length);
    for (int j = 0; j < length; ++j) s += (j ? ", " : "") + literal(j < int(k.size()) ? k[std::size_t(j)] : 0.0f);
    return s + ");\n";
}

// flip_constants.glsl: the pass, the kernels and the color constants, each the float the CPU code
// computes with.
std::string constants(const LdrFlip& cpu, int pass, std::uint32_t run) {
    const flip::CsfKernels& csf = cpu.csf_kernels();
    const flip::FeatureKernels& features = cpu.feature_kernels();
    const int max_radius = std::max(csf.radius, features.radius);
    std::string s = fmt::format("#define FLIP_PASS {}\n#define CSF_RADIUS {}\n#define FEATURE_RADIUS {}\n"
                                "#define MAX_RADIUS {}\n#define FLIP_RUN {}\n#define FLIP_WINDOW {}\n",
                                pass, csf.radius, features.radius, max_radius, run, run + 2 * max_radius);
    s += weights("CSF_Y", csf.achromatic, max_radius + 1);
    s += weights("CSF_CX", csf.red_green, max_radius + 1);
    s += weights("CSF_CZ1", csf.blue_yellow_1, max_radius + 1);
    s += weights("CSF_CZ2", csf.blue_yellow_2, max_radius + 1);
    s += weights("FEATURE_GAUSSIAN", features.gaussian, max_radius + 1);
    s += weights("FEATURE_EDGE", features.edge, max_radius + 1);
    s += weights("FEATURE_POINT", features.point, max_radius + 1);
    auto define = [&](const std::string& name, float v) { s += fmt::format("#define {} {}\n", name, literal(v)); };
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            define(fmt::format("RGB_TO_XYZ_{}{}", r, c), float(flip::kLinearRgbToXyz[r][c]));
            define(fmt::format("XYZ_TO_RGB_{}{}", r, c), float(flip::kXyzToLinearRgb[r][c]));
        }
    define("WHITE_X", float(flip::kD65White[0]));
    define("WHITE_Y", float(flip::kD65White[1]));
    define("WHITE_Z", float(flip::kD65White[2]));
    // The color error's remapping, as LdrFlip::evaluate computes each part in float.
    const float cmax = cpu.max_color_distance(), pc_cmax = cpu.pc_max_color_distance();
    define("QC", flip::kQc);
    define("PT", flip::kPt);
    define("PC_CMAX", pc_cmax);
    define("PT_OVER_PC_CMAX", flip::kPt / pc_cmax);
    define("CMAX_MINUS_PC_CMAX", cmax - pc_cmax);
    define("ONE_MINUS_PT", 1.0f - flip::kPt);
    define("INV_SQRT2", float(1.0 / std::numbers::sqrt2));
    for (auto [name, mapper] : {std::pair{"ACES", ToneMapper::aces}, std::pair{"HABLE", ToneMapper::hable}}) {
        const ToneCurve& k = tone_curve(mapper);
        if (k.c != 0.0f) return "#error the tone curve's c is not 0\n"; // the shader leaves it out
        define(fmt::format("{}_A", name), k.a);
        define(fmt::format("{}_B", name), k.b);
        define(fmt::format("{}_D", name), k.d);
        define(fmt::format("{}_E", name), k.e);
        define(fmt::format("{}_F", name), k.f);
    }
    return s;
}

} // namespace

// Pixels each invocation of the filter passes computes along the filter's direction (the
// template's FLIP_RUN; `pass` is its FLIP_PASS: 0 horizontal, 1 vertical). On a CPU device
// (lavapipe) the neighbors' fetches (and, horizontally, their color transforms) are then shared
// within an invocation, in registers; the lengths are the cheapest measured (docs/results.md,
// "FLIP on lavapipe: run lengths"). A GPU has the loads cached and lanes to spare.
std::uint32_t flip_run_length(const Context& context, int pass) {
    if (context.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU) return 1;
    return pass == 0 ? 8u : pass == 1 ? 24u : 1u;
}

Result<std::unique_ptr<RunnableVariant>> build_flip_pass(const LdrFlip& cpu, int pass, std::uint32_t run) {
    static constexpr const char* kNames[] = {"flip-horizontal", "flip-vertical", "flip-row-sums", "flip-load",
                                             "flip-luminance"};
    auto source = find_embedded_file(kTemplate);
    if (!source) return fail(fmt::format("internal error: {} is not embedded", kTemplate));
    BuiltVariant built;
    built.spec.mode = Mode::shader;
    built.name = kNames[pass];
    built.compute_glsl = std::string(*source);
    const std::string file = built.name + ".comp";
    const std::string defines = constants(cpu, pass, run);
    IncludeResolver resolve = [&](std::string_view header, std::string_view) -> std::optional<IncludedSource> {
        if (header == "flip_constants.glsl") return IncludedSource{built.name + "/flip_constants.glsl", defines};
        return std::nullopt;
    };
    auto compiled = compile_glsl_compute(built.compute_glsl, file, TargetEnv::vulkan1_0, resolve);
    // Unoptimized: the passes are written unrolled, and SPIRV-Tools takes seconds over their
    // thousands of taps for nothing the driver's compiler does not do.
    if (auto ok = compile_into(built, built.compute_glsl, file, TargetEnv::vulkan1_0, std::move(compiled),
                               SpirvOptimization::none);
        !ok)
        return std::unexpected(ok.error());
    return std::make_unique<RunnableVariant>(std::move(built));
}

} // namespace kdop
