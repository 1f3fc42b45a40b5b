#include "sequence/sequence_corpus.h"

#include "core/read_file.h"
#include "core/shown_text.h"

#include <fmt/format.h>

#include <algorithm>
#include <system_error>

namespace kdop {
namespace {

namespace fs = std::filesystem;

bool is_sequence(const fs::path& dir) {
    std::error_code ec;
    return fs::is_regular_file(dir / "sequence.json", ec);
}

// The subfolders of `dir` that hold a sequence, in byte order of their names.
std::vector<std::string> sequences_in(const fs::path& dir) {
    std::vector<std::string> found;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_directory(ec) && is_sequence(it->path())) found.push_back(it->path().string());
    std::sort(found.begin(), found.end());
    return found;
}

// `arg`'s sequences: itself, or its subfolders'; none where it is neither.
std::vector<std::string> folder_sequences(const std::string& arg) {
    if (is_sequence(arg)) return {arg};
    std::error_code ec;
    if (!fs::is_directory(arg, ec)) return {};
    return sequences_in(arg);
}

} // namespace

Result<std::vector<std::string>> parse_sequence_list(std::string_view text, const fs::path& file) {
    std::vector<std::string> folders;
    std::size_t line_number = 0;
    for (std::size_t start = 0; start <= text.size();) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        std::string_view line = text.substr(start, end - start);
        start = end + 1;
        ++line_number;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        if (line.find('\0') != std::string_view::npos)
            return fail(fmt::format("{}:{}: a NUL byte in a folder's name", file.string(), line_number));
        if (line.empty() || line.front() == '#') continue;
        const fs::path folder(line);
        folders.push_back(folder.is_absolute() ? folder.string() : (file.parent_path() / folder).string());
    }
    if (folders.empty()) return fail(fmt::format("{}: a list of sequences that names none", file.string()));
    return folders;
}

Result<std::vector<std::string>> expand_sequence_arguments(std::span<const std::string> given,
                                                           std::string_view option) {
    std::vector<std::string> out;
    for (const std::string& arg : given) {
        std::error_code ec;
        if (fs::is_regular_file(arg, ec)) {
            auto text = read_input_file(arg);
            if (!text) return fail(fmt::format("{} {}: {}", option, shown_text(arg, 200), text.error().message));
            auto listed = parse_sequence_list(*text, arg);
            if (!listed) return fail(fmt::format("{}: {}", option, listed.error().message));
            for (const std::string& folder : *listed) {
                std::vector<std::string> found = folder_sequences(folder);
                if (found.empty())
                    return fail(fmt::format("{} {}: names {}, which is neither a sequence's folder (with "
                                            "sequence.json) nor a folder of sequences",
                                            option, shown_text(arg, 200), shown_text(folder, 200)));
                out.insert(out.end(), found.begin(), found.end());
            }
            continue;
        }
        std::vector<std::string> found = folder_sequences(arg);
        if (found.empty())
            return fail(fmt::format("{} {}: neither a sequence's folder (with sequence.json), nor a folder of "
                                    "sequences (subfolders with one), nor a list of them (a file, one folder a line)",
                                    option, shown_text(arg, 200)));
        out.insert(out.end(), found.begin(), found.end());
    }
    return out;
}

Result<std::vector<std::string>> nss_sequences(const fs::path& root) {
    std::vector<std::pair<unsigned long long, std::string>> found;
    std::error_code ec;
    for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
        const fs::path& p = it->path();
        const std::string stem = p.stem().string();
        if (p.extension() != ".json" || stem.size() < 4 || stem.size() > 18 ||
            !std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; }))
            continue;
        found.emplace_back(std::stoull(stem), stem);
    }
    if (ec) return fail(fmt::format("{}: {}", root.string(), ec.message()));
    if (found.empty()) return fail(fmt::format("{}: no NNNN.json there, so no NSS sequence to measure", root.string()));
    std::sort(found.begin(), found.end());
    std::vector<std::string> names;
    for (auto& [number, name] : found) names.push_back(std::move(name));
    return names;
}

} // namespace kdop
