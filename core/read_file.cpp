#include "core/read_file.h"

#include "core/input_files.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace kdop {
namespace fs = std::filesystem;

std::optional<std::string> not_a_readable_file(const fs::path& path) {
    if (path.empty()) return "no file named (an empty path)";
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (status.type() == fs::file_type::not_found) return "does not exist";
    if (ec) return ec.message();
    if (status.type() == fs::file_type::directory) return "is a directory, not a file";
    if (status.type() != fs::file_type::regular)
        return "is not a regular file (a device, pipe or socket); kdop reads files";
    return std::nullopt;
}

Result<std::string> read_own_file(const fs::path& path) {
    if (auto why = not_a_readable_file(path)) return fail(fmt::format("{}: {}", path.string(), *why));
    std::ifstream in(path, std::ios::binary);
    if (!in) return fail(fmt::format("{}: cannot open: {}", path.string(), std::strerror(errno)));
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) return fail(fmt::format("{}: read error", path.string()));
    return text.str();
}

Result<std::string> read_input_file(const fs::path& path) {
    auto text = read_own_file(path);
    if (text) note_input(path);
    return text;
}

std::optional<std::string> read_file(const fs::path& path) {
    auto text = read_input_file(path);
    if (!text) return std::nullopt;
    return std::move(*text);
}

} // namespace kdop
