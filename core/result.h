// Errors as values: every fallible step returns Result<T>, whose error is a message ready for
// stderr that names the file, line or argument and the reason ("dop22.axes:7: axis has zero length").
#pragma once

#include <expected>
#include <string>

namespace kdop {

struct Error {
    std::string message;
    bool usage = false; // the command line is at fault (a value, or options that do not go together): exit 2
};

template <class T>
using Result = std::expected<T, Error>;

inline std::unexpected<Error> fail(std::string message) { return std::unexpected(Error{std::move(message)}); }

// An error the command line caused, found by a library call: the command reports it as a usage error.
inline std::unexpected<Error> usage_fail(std::string message) {
    return std::unexpected(Error{std::move(message), true});
}

} // namespace kdop
