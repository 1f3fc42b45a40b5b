// kdop: generate, run and measure k-DOP neighborhood-clipping variants. See README.md.
#include "cli/commands.h"

#include "core/memory_budget.h"
#include "generator/command_line.h"
#include "harness/ranks.h"
#include "harness/run_metadata.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <map>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    kdop::return_large_blocks_when_freed();
    kdop::record_command_line(argc, argv);
    CLI::App app{"kdop: k-DOP neighborhood clipping for temporal antialiasing: generate shader variants, run them, "
                 "measure them"};
    app.require_subcommand(1);
    struct Registered {
        kdop::cli::Action action;
        bool shares_over_ranks;
    };
    std::map<std::string, Registered> commands; // by name
    std::vector<std::string> sharing;           // "kdop <name>" of those that share over ranks
    for (const kdop::cli::Command& command : kdop::cli::kCommands) {
        kdop::cli::Action action = command.add(app);
        const std::string name = app.get_subcommands({}).back()->get_name();
        commands.emplace(name, Registered{action, command.shares_over_ranks});
        if (command.shares_over_ranks) sharing.push_back("kdop " + name);
    }
    return kdop::run_command_line(app, "kdop", argc, argv, [&] {
        for (CLI::App* chosen : app.get_subcommands()) {
            const Registered& command = commands.at(chosen->get_name());
            if (!command.shares_over_ranks && kdop::launched_ranks() > 1)
                return kdop::cli::usage_error(fmt::format("{}: only {} share their work over MPI ranks; run kdop {} "
                                                          "without mpirun",
                                                          chosen->get_name(), fmt::join(sharing, " and "),
                                                          chosen->get_name()));
            return command.action();
        }
        return 1;
    });
}
