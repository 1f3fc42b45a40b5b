#include "core/builtin_sets.h"

#include "core/embedded_files.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <vector>

namespace kdop {
namespace {

constexpr std::string_view kFolder = "shader_templates/axis_sets/";

// Lines that hold an axis: not blank, not a comment, not the name or provenance line. A count for
// ordering only; the generator's parser (axis_set.h) validates the file.
std::size_t axis_lines(std::string_view text) {
    std::istringstream in{std::string(text)};
    std::size_t count = 0;
    for (std::string line; std::getline(in, line);) {
        line = line.substr(0, line.find('#'));
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos) continue;
        const std::string_view content = std::string_view(line).substr(first);
        if (!content.starts_with("name:") && !content.starts_with("provenance:")) ++count;
    }
    return count;
}

std::vector<std::string> discover() {
    std::vector<std::pair<std::size_t, std::string>> sets;
    for (const EmbeddedFile& f : embedded_files())
        if (f.path.starts_with(kFolder) && f.path.ends_with(".axes"))
            sets.emplace_back(axis_lines(f.text), std::filesystem::path(f.path).stem().string());
    std::sort(sets.begin(), sets.end());
    std::vector<std::string> names;
    for (auto& [axes, name] : sets) names.push_back(std::move(name));
    return names;
}

} // namespace

std::span<const std::string> builtin_set_names() {
    static const std::vector<std::string> names = discover();
    return names;
}

std::string builtin_set_list() { return fmt::format("{}", fmt::join(builtin_set_names(), ", ")); }

bool is_builtin_set(std::string_view name) {
    const auto names = builtin_set_names();
    return std::find(names.begin(), names.end(), name) != names.end();
}

std::string builtin_set_path(std::string_view name) { return fmt::format("{}{}.axes", kFolder, name); }

std::optional<std::string_view> builtin_set_text(std::string_view name) {
    if (!is_builtin_set(name)) return std::nullopt;
    return find_embedded_file(builtin_set_path(name));
}

} // namespace kdop
