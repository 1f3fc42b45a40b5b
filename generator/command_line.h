// How every kdop program ends: a usage error prints CLI11's message and exits 2 (--help and
// --version exit 0); a failure the body reports is a message and exit 1 (the body returns it); and
// an exception that escapes the body (memory, a library) is a message and exit 1 too, never an abort;
// a signal that would end the run (SIGINT, SIGTERM, SIGHUP, SIGPIPE, ...) removes what it left
// unfinished and exits 128 + its number (core/interrupt.h); and no output may replace a file the
// run read (core/input_files.h).
#pragma once

#include "core/input_files.h"
#include "core/interrupt.h"
#include "core/shown_text.h"

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>
#include <new>
#include <string>

namespace kdop {

inline constexpr int kUsageError = 2;

// Parses the command line into `app`, then returns `body()`'s exit status. `program` names the
// program in the messages of escaped exceptions.
template <class Body>
int run_command_line(CLI::App& app, const char* program, int argc, char** argv, Body body) {
    handle_interrupts(program); // before any thread starts, so that every one inherits the mask
    protect_inputs();           // no output of this run may replace a file it read
    app.set_version_flag("--version", std::string(program) + " " + KDOP_VERSION);
    // Every message says whose it is, as compilers' do ("glslc: error: ..."), and is one line, as
    // kdop's own usage errors are (CLI11 would add "Run with --help for more information.").
    app.failure_message([program](const CLI::App*, const CLI::Error& e) {
        return std::string(program) + ": " + terminal_text(e.what()) + "\n";
    });
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // A mistyped command reads better as that than as "A subcommand is required".
        std::string commands;
        bool known = false;
        for (const CLI::App* command : app.get_subcommands({}))
            if (!command->get_name().empty()) {
                commands += (commands.empty() ? "" : ", ") + command->get_name();
                known = known || (argc > 1 && command->get_name() == argv[1]);
            }
        if (argc > 1 && argv[1][0] != '-' && !known && !commands.empty()) {
            std::cerr << program << ": '" << terminal_text(argv[1]) << "' is not a command; the commands: " << commands
                      << " (see --help)\n";
            return kUsageError;
        }
        return app.exit(e) == 0 ? 0 : kUsageError;
    }
    try {
        return body();
    } catch (const std::bad_alloc&) {
        std::cerr << program << ": out of memory\n";
    } catch (const std::exception& e) {
        std::cerr << program << ": " << terminal_text(e.what()) << "\n";
    }
    return 1;
}

} // namespace kdop
