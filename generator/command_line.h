// How every kdop program ends: a usage error prints CLI11's message and exits 2 (--help and
// --version exit 0); a failure the body reports is a message and exit 1 (the body returns it); and
// an exception that escapes the body (memory, a library) is a message and exit 1 too, never an abort.
#pragma once

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
    app.set_version_flag("--version", std::string(program) + " " + KDOP_VERSION);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : kUsageError;
    }
    try {
        return body();
    } catch (const std::bad_alloc&) {
        std::cerr << program << ": out of memory\n";
    } catch (const std::exception& e) {
        std::cerr << program << ": " << e.what() << "\n";
    }
    return 1;
}

} // namespace kdop
