#include "core/output_listing.h"

#include "core/input_files.h"
#include "core/read_file.h"
#include "core/shown_text.h"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <set>

namespace kdop {
namespace fs = std::filesystem;

namespace {

constexpr std::string_view kHeader =
    "# The files kdop's last run wrote in this folder; the next run here removes those it does not write again.\n";

// Why `entry` is not a plain relative path inside the folder, or empty when it is.
std::string entry_problem(std::string_view entry) {
    if (entry.starts_with('/')) return "is an absolute path";
    for (char c : entry)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return "holds a control byte";
    std::size_t start = 0;
    while (true) {
        const std::size_t slash = entry.find('/', start);
        const std::string_view part = entry.substr(start, slash == std::string_view::npos ? slash : slash - start);
        if (part.empty() || part == "." || part == "..")
            return fmt::format("has a '{}' component; entries are paths inside the folder", part);
        if (slash == std::string_view::npos) return {};
        start = slash + 1;
    }
}

} // namespace

std::string output_listing_text(std::vector<std::string> files) {
    // A file outside the folder (an output named by its own option) is not the folder's to list.
    std::erase_if(files, [](const std::string& f) { return !entry_problem(f).empty(); });
    std::sort(files.begin(), files.end());
    files.erase(std::unique(files.begin(), files.end()), files.end());
    std::string text(kHeader);
    for (const std::string& f : files) text += f + "\n";
    return text;
}

Result<std::vector<std::string>> parse_output_listing(std::string_view text, const std::string& origin) {
    std::vector<std::string> entries;
    std::size_t line_number = 0;
    while (!text.empty()) {
        ++line_number;
        const std::size_t end = text.find('\n');
        std::string_view line = text.substr(0, end);
        text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
        if (line.ends_with('\r')) line.remove_suffix(1);
        if (line.empty() || line.starts_with('#')) continue;
        if (const std::string problem = entry_problem(line); !problem.empty())
            return fail(fmt::format("{}:{}: '{}' {}; this file lists what kdop wrote in the folder: correct the line "
                                    "or remove the file",
                                    origin, line_number, shown_text(line, 200), problem));
        entries.emplace_back(line);
    }
    return entries;
}

Result<std::vector<std::string>> read_output_listing(const fs::path& dir) {
    const fs::path path = dir / kOutputListingName;
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(path, ec))) return std::vector<std::string>{};
    auto text = read_own_file(path);
    if (!text) return std::unexpected(text.error());
    return parse_output_listing(*text, path.string());
}

std::vector<fs::path> stale_outputs(const fs::path& dir, const std::vector<std::string>& listed,
                                    const std::vector<std::string>& kept) {
    const std::set<std::string> writing(kept.begin(), kept.end());
    std::vector<fs::path> stale;
    for (const std::string& entry : listed) {
        if (writing.contains(entry) || !entry_problem(entry).empty()) continue;
        // Every folder on the way, and the file itself, as they are, not through a link.
        fs::path at = dir;
        bool plain = true;
        const fs::path relative(entry);
        for (auto part = relative.begin(); plain && part != relative.end(); ++part) {
            at /= *part;
            std::error_code ec;
            const fs::file_status status = fs::symlink_status(at, ec);
            const bool last = std::next(part) == relative.end();
            plain = !ec && (last ? fs::is_regular_file(status) : fs::is_directory(status));
        }
        if (plain && !noted_input_at(at)) stale.push_back(at);
    }
    return stale;
}

} // namespace kdop
