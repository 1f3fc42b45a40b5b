#include "cli/commands.h"

#include "cli/variant_option.h"
#include "generator/clip_emitter.h"
#include "generator/variant_builder.h"
#include "harness/variant_catalog.h"

#include <fmt/format.h>

#include <iostream>
#include <memory>

namespace kdop::cli {

Action add_show_command(CLI::App& app) {
    struct Options {
        std::string name;
        std::vector<std::string> sets;
        std::string numerics;
        bool compute = false, hlsl = false, wgsl = false;
    };
    auto options = std::make_shared<Options>();
    CLI::App* show = app.add_subcommand(
        "show", "Print a variant's GLSL, HLSL or WGSL function (or, with --compute, its compute shader)");
    show->add_option("NAME", options->name, "Variant name, e.g. dop32-clip-n9 (see `kdop list --all`)")->required();
    show->add_option("--sets", options->sets, "Axis-set files to look in besides the built-in sets");
    show->add_option(
            "--numerics", options->numerics,
            "hardened, or paper: the variant with the supplement's numerics (the same as naming <variant>-paper)")
        ->check(CLI::IsMember({"hardened", "paper"}));
    show->add_flag("--compute", options->compute, "Print the whole compute shader instead of the includable function");
    CLI::Option* hlsl = show->add_flag(
        "--hlsl", options->hlsl, "The HLSL function (with --compute, the HLSL compute shader the tests run it in)");
    show->add_flag("--wgsl", options->wgsl, "The WGSL function (WebGPU, Bevy)")
        ->excludes(hlsl)
        ->excludes(show->get_option("--compute"));

    return [options] {
        auto key = variant_option(options->name, options->numerics, "show");
        // The name and its set come from the command line: refusing them is a usage error.
        if (!key) return usage_error(key.error().message);
        auto catalog = VariantCatalog::create(options->sets);
        if (!catalog) return report_error(catalog.error().message);
        auto spec = catalog->spec(*key, "show");
        if (!spec) return usage_error(spec.error().message);
        if (!options->compute) {
            std::cout << emit_function(*spec, options->wgsl ? kWgsl : options->hlsl ? kHlsl : kGlsl);
            return 0;
        }
        // Builds, so the shader shown is one that compiles.
        auto built = build_variant(*spec, options->hlsl ? SourceLanguage::hlsl : SourceLanguage::glsl);
        if (!built) return report_error(built.error().message);
        std::cout << (options->hlsl ? built->compute_hlsl : built->compute_glsl);
        return 0;
    };
}

} // namespace kdop::cli
