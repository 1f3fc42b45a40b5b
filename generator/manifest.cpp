#include "generator/manifest.h"

#include "core/builtin_sets.h"
#include "core/read_file.h"
#include "core/shown_text.h"
#include "generator/inside_folder.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace kdop {
namespace fs = std::filesystem;

namespace {

std::string_view trimmed(std::string_view s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

} // namespace

Result<Manifest> read_manifest(const fs::path& path) {
    auto content = read_input_file(path);
    if (!content) return fail(fmt::format("{} (the manifest)", content.error().message));
    std::string_view rest = *content;
    if (rest.starts_with("\xEF\xBB\xBF")) rest.remove_prefix(3); // a UTF-8 byte-order mark some editors write
    Manifest manifest;
    std::map<std::string, AxisSet> declared; // `set:` files by set name
    int number = 0;
    while (!rest.empty()) {
        const std::size_t end = std::min(rest.find('\n'), rest.size());
        const std::string_view text = rest.substr(0, end);
        rest.remove_prefix(std::min(end + 1, rest.size()));
        ++number;
        const std::string where = fmt::format("{}:{}", path.string(), number);
        std::string_view line = trimmed(text.substr(0, text.find('#')));
        if (line.empty()) continue;

        if (line.starts_with("set:")) {
            const std::string_view named = trimmed(line.substr(4));
            if (named.empty()) return fail(fmt::format("{}: `set:` names no axis-set file", where));
            const fs::path file = path.parent_path() / named;
            // Confined as a shader's includes are: `set: /etc/passwd` read the file and echoed its
            // lines in the parse errors ("/etc/passwd:1: unknown key 'root'"). It is refused unread.
            if (!is_inside_folder(file, path.parent_path()))
                return fail(
                    fmt::format("{}: `set: {}` names a file outside the manifest's folder ({}); a manifest "
                                "reads axis files only from its folder and below it, links resolved",
                                where, shown_text(named, 200),
                                shown_text(path.parent_path().empty() ? "." : path.parent_path().string(), 200)));
            auto set_text = read_input_file(file);
            if (!set_text)
                return fail(fmt::format("{}: cannot read the axis-set file it names: {}", where,
                                        shown_text(set_text.error().message, 300)));
            auto set = parse_axis_set(*set_text, file.string()); // its errors name the file and line
            if (!set) return fail(fmt::format("{}: in the set it names: {}", where, set.error().message));
            if (is_builtin_set(set->name) || declared.count(set->name))
                return fail(fmt::format("{}: {} names its set '{}', which {}", where, shown_text(file.string(), 200),
                                        set->name,
                                        declared.count(set->name) ? "an earlier set: line gives" : "is built in"));
            manifest.set_files.push_back(file);
            declared.emplace(set->name, std::move(*set));
            continue;
        }

        auto key = parse_variant_key(line, where);
        if (!key) return std::unexpected(key.error());
        VariantSpec spec{{}, key->mode, key->neighborhood, key->form, key->numerics};
        if (key->is_clip()) {
            if (auto found = declared.find(key->set); found != declared.end())
                spec.set = found->second;
            else if (is_builtin_set(key->set))
                spec.set = *resolve_axis_set(key->set); // built in: cannot fail
            else
                return fail(fmt::format("{}: '{}' is of set '{}', which is neither built in ({}) nor given by a "
                                        "`set: FILE` line above",
                                        where, line, key->set, builtin_set_list()));
        }
        if (std::any_of(manifest.variants.begin(), manifest.variants.end(),
                        [&](const VariantSpec& s) { return s.key() == spec.key(); }))
            return fail(fmt::format("{}: '{}' is listed twice", where, line));
        manifest.variants.push_back(std::move(spec));
    }
    if (manifest.variants.empty()) return fail(fmt::format("{}: lists no variant", path.string()));
    return manifest;
}

} // namespace kdop
