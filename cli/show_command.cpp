#include "commands.h"

#include "glsl_emitter.h"
#include "variant_builder.h"
#include "variant_catalog.h"

#include <fmt/format.h>

#include <iostream>
#include <memory>

namespace kdop::cli {

Action add_show_command(CLI::App& app) {
    struct Options {
        std::string name;
        std::vector<std::string> sets;
        std::string numerics;
        bool compute = false;
    };
    auto options = std::make_shared<Options>();
    CLI::App* show =
        app.add_subcommand("show", "Print a variant's GLSL function (or, with --compute, its compute shader)");
    show->add_option("NAME", options->name, "Variant name, e.g. dop32-clip-n9 (see `kdop list --all`)")->required();
    show->add_option("--sets", options->sets, "Axis-set files to look in besides the built-in sets");
    show->add_option(
            "--numerics", options->numerics,
            "hardened, or paper: the variant with the supplement's numerics (the same as naming <variant>-paper)")
        ->check(CLI::IsMember({"hardened", "paper"}));
    show->add_flag("--compute", options->compute, "Print the whole compute shader instead of the includable function");

    return [options] {
        auto key = parse_variant_key(options->name, "show");
        if (!key) return report_error(key.error().message);
        if (!options->numerics.empty()) {
            if (!key->is_clip()) return report_error(fmt::format("--numerics: {} is not a clip", options->name));
            if (key->numerics == Numerics::paper && options->numerics != "paper")
                return report_error(
                    fmt::format("--numerics: {} conflicts with the variant's own -paper", options->numerics));
            key = key->with(*parse_numerics(options->numerics));
        }
        auto catalog = VariantCatalog::create(options->sets);
        if (!catalog) return report_error(catalog.error().message);
        VariantSpec spec{{}, key->mode, key->neighborhood, key->form, key->numerics};
        if (key->is_clip()) {
            auto set = catalog->set(key->set, "show");
            if (!set) return report_error(set.error().message);
            spec.set = std::move(*set);
        }
        if (!options->compute) {
            std::cout << emit_function(spec);
            return 0;
        }
        auto built = build_variant(spec); // builds, so the shader shown is one that compiles
        if (!built) return report_error(built.error().message);
        std::cout << built->compute_glsl;
        return 0;
    };
}

} // namespace kdop::cli
