// Errors as values: every fallible step returns Result<T>, whose error is a message ready for
// stderr that names the file, line or argument and the reason ("dop22.axes:7: axis has zero length").
#pragma once

#include <expected>
#include <string>

namespace kdop {

struct Error {
    std::string message;
};

template <class T>
using Result = std::expected<T, Error>;

inline std::unexpected<Error> fail(std::string message) { return std::unexpected(Error{std::move(message)}); }

} // namespace kdop
