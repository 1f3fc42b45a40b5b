// kdop: generate, run and measure k-DOP neighborhood-clipping variants. See README.md.
#include "cli/commands.h"

#include "core/memory_budget.h"
#include "generator/command_line.h"
#include "harness/ranks.h"
#include "harness/run_metadata.h"

#include <fmt/format.h>

#include <map>

int main(int argc, char** argv) {
    kdop::return_large_blocks_when_freed();
    kdop::record_command_line(argc, argv);
    CLI::App app{"kdop: k-DOP neighborhood clipping for temporal antialiasing: generate shader variants, run them, "
                 "measure them"};
    app.require_subcommand(1);
    std::map<std::string, kdop::cli::Action> actions{
        {"list", kdop::cli::add_list_command(app)},         {"gen", kdop::cli::add_gen_command(app)},
        {"show", kdop::cli::add_show_command(app)},         {"run", kdop::cli::add_run_command(app)},
        {"textures", kdop::cli::add_textures_command(app)}, {"bench", kdop::cli::add_bench_command(app)},
        {"stress", kdop::cli::add_stress_command(app)},     {"accuracy", kdop::cli::add_accuracy_command(app)},
        {"optimize", kdop::cli::add_optimize_command(app)}, {"flip", kdop::cli::add_flip_command(app)},
        {"taa", kdop::cli::add_taa_command(app)},           {"scene", kdop::cli::add_scene_command(app)},
        {"choose", kdop::cli::add_choose_command(app)},
    };
    return kdop::run_command_line(app, "kdop", argc, argv, [&] {
        for (CLI::App* chosen : app.get_subcommands()) {
            // Every rank would do the whole of any other command and write the same outputs.
            const bool shares = chosen->get_name() == "optimize" || chosen->get_name() == "choose";
            if (!shares && kdop::launched_ranks() > 1)
                return kdop::cli::usage_error(fmt::format("{}: only kdop optimize and kdop choose share their work "
                                                          "over MPI ranks; run kdop {} without mpirun",
                                                          chosen->get_name(), chosen->get_name()));
            return actions.at(chosen->get_name())();
        }
        return 1;
    });
}
