#include "commands.h"

#include "glsl_emitter.h"
#include "variant_builder.h"

#include <fmt/format.h>

#include <iostream>
#include <memory>

namespace kdop::cli {

Action add_show_command(CLI::App& app) {
    struct Options {
        std::string name;
        std::vector<std::string> sets;
        bool compute = false;
    };
    auto options = std::make_shared<Options>();
    CLI::App* show = app.add_subcommand("show", "Print a variant's GLSL function (or, with --compute, its compute shader)");
    show->add_option("NAME", options->name, "Variant name, e.g. dop32-clip-n9 (see `kdop list --all`)")->required();
    show->add_option("--sets", options->sets, "Axis-set files to look in besides the built-in sets");
    show->add_flag("--compute", options->compute, "Print the whole compute shader instead of the includable function");

    return [options] {
        std::vector<VariantSpec> specs = all_builtin_variants();
        if (!options->sets.empty()) {
            auto user = select_variants(options->sets, {}, {}, {"unrolled", "loop"});
            if (!user) return report_error(user.error().message);
            specs.insert(specs.end(), user->begin(), user->end());
        }
        for (const VariantSpec& spec : specs) {
            if (variant_name(spec) != options->name) continue;
            if (!options->compute) {
                std::cout << emit_function(spec);
                return 0;
            }
            auto built = build_variant(spec); // builds, so the shader shown is one that compiles
            if (!built) return report_error(built.error().message);
            std::cout << built->compute_glsl;
            return 0;
        }
        return report_error(fmt::format("show: unknown variant '{}' (see `kdop list --all`; a user set needs --sets FILE)",
                                        options->name));
    };
}

} // namespace kdop::cli
