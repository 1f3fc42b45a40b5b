#include "commands.h"

#include "variant_spec.h"

#include <iostream>

namespace kdop::cli {

Action add_list_command(CLI::App& app) {
    app.add_subcommand("list", "Print the name of every default variant, one per line");
    return [] {
        auto specs = select_variants({}, {}, {});
        if (!specs) return report_error(specs.error().message);
        for (const VariantSpec& spec : *specs) std::cout << variant_name(spec) << '\n';
        return 0;
    };
}

} // namespace kdop::cli
