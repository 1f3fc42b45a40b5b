#include "cli/commands.h"

#include "generator/manifest.h"
#include "generator/selection_options.h"
#include "generator/variant_spec.h"

#include <iostream>
#include <memory>
#include <string>

namespace kdop::cli {

Action add_list_command(CLI::App& app) {
    struct Options {
        bool all = false;
        std::string manifest;
        std::vector<std::string> sets;
    };
    auto o = std::make_shared<Options>();
    CLI::App* list = app.add_subcommand("list", "Print the name of every default variant, one per line");
    auto* all =
        list->add_flag("--all", o->all, "Also the loop-form baselines (<variant>-loop) and gather-n9, gather-n5, copy");
    auto* manifest =
        list->add_option("--manifest", o->manifest, "Only the variants a scene's manifest lists, in its order")
            ->excludes(all);
    list->add_option("--sets", o->sets,
                     "Only the variants of these axis sets: built-in names or your files (with --all, their loop "
                     "forms too)")
        ->check(SelectionOptions::axis_set_name())
        ->excludes(manifest);
    return [o] {
        if (!o->manifest.empty()) {
            auto manifest = read_manifest(o->manifest);
            if (!manifest) return report_error(manifest.error().message);
            for (const VariantSpec& spec : manifest->variants) std::cout << variant_name(spec) << '\n';
            return 0;
        }
        auto specs = !o->sets.empty() ? select_variants(o->sets, {}, {},
                                                        o->all ? std::vector<std::string>{"unrolled", "loop"}
                                                               : std::vector<std::string>{})
                     : o->all ? Result<std::vector<VariantSpec>>(all_builtin_variants())
                                      : select_variants({}, {}, {});
        if (!specs) return report_error(specs.error().message);
        for (const VariantSpec& spec : *specs) std::cout << variant_name(spec) << '\n';
        return 0;
    };
}

} // namespace kdop::cli
