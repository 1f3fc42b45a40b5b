// kdop's subcommands. Each add_*_command registers its options on the parent app and returns the
// action to run when that subcommand was chosen; the action returns the process exit code.
#pragma once

#include "core/color_map.h"
#include "generator/variant_spec.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <span>
#include <string>
#include <string_view>

namespace kdop::cli {

using Action = std::function<int()>;

Action add_list_command(CLI::App& app);
Action add_gen_command(CLI::App& app);
Action add_show_command(CLI::App& app);
Action add_run_command(CLI::App& app);
Action add_textures_command(CLI::App& app);
Action add_bench_command(CLI::App& app);
Action add_stress_command(CLI::App& app);
Action add_accuracy_command(CLI::App& app);
Action add_optimize_command(CLI::App& app);
Action add_flip_command(CLI::App& app);
Action add_taa_command(CLI::App& app);
Action add_scene_command(CLI::App& app);
Action add_choose_command(CLI::App& app);

// One of kdop's commands: what registers it, and whether it shares its work over MPI ranks (every
// other command refuses to run under mpirun: each rank would do all of it and write the same files).
struct Command {
    Action (*add)(CLI::App& app);
    bool shares_over_ranks = false;
};
// Every command, in the order --help lists them.
inline constexpr Command kCommands[] = {
    {add_list_command},           {add_gen_command},   {add_show_command},      {add_run_command},
    {add_textures_command},       {add_bench_command}, {add_stress_command},    {add_accuracy_command},
    {add_optimize_command, true}, {add_flip_command},  {add_taa_command, true}, {add_scene_command},
    {add_choose_command, true},
};

// Prints an error message (which already names file/line or argument) to stderr; returns 1.
int report_error(const std::string& message);

// The same for a wrong command line (an option's value, options that do not go together); returns
// 2, as CLI11's own usage errors do.
int usage_error(const std::string& message);

// A library call's error: usage_error where the command line is at fault (Error::usage), else
// report_error.
int report(const Error& error);

// Prints what the validation layer reported (nothing when it was off) to stderr.
void report_validation_messages(std::span<const std::string> messages);

// Warns on stderr, once per set, about every set of `specs` fitted in another space than `used`,
// the one `clipping` clips in (generator/axis_set.h, fitted_space_mismatch).
void warn_fitted_space(std::span<const VariantSpec> specs, const ColorMap& used, std::string_view clipping);

} // namespace kdop::cli
