#include "commands.h"

#include "variant_spec.h"

#include <iostream>
#include <memory>

namespace kdop::cli {

Action add_list_command(CLI::App& app) {
    auto all = std::make_shared<bool>(false);
    CLI::App* list = app.add_subcommand("list", "Print the name of every default variant, one per line");
    list->add_flag("--all", *all, "Also the loop-form baselines (<variant>-loop) and gather-n9, gather-n5, copy");
    return [all] {
        auto specs = *all ? Result<std::vector<VariantSpec>>(all_builtin_variants()) : select_variants({}, {}, {});
        if (!specs) return report_error(specs.error().message);
        for (const VariantSpec& spec : *specs) std::cout << variant_name(spec) << '\n';
        return 0;
    };
}

} // namespace kdop::cli
