#include "generator/manifest.h"

#include "core/builtin_sets.h"
#include "core/color_map.h"
#include "core/read_file.h"
#include "core/shown_text.h"
#include "core/upscale_settings.h"
#include "generator/inside_folder.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>

namespace kdop {
namespace fs = std::filesystem;

namespace {

std::string_view trimmed(std::string_view s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// The resolve's keys, in the order resolve_lines writes them; then those of a resolve that
// upscaled, all three or none.
constexpr std::string_view kResolveKeys[] = {"gamma", "current-weight", "color-map", "history-filter", "dilate-motion"};
constexpr std::string_view kUpscaleKeys[] = {"upscale-filter", "upscale-sample-distance", "upscale-box-scale"};

// A decimal above 0 and at most `max`, as float: the commands' numbers (cli/number_option.h), so
// "0x10", " 5" and "inf" are refused; a value float cannot hold above 0 (1e-50) is refused too.
Result<float> positive_float(std::string_view text, double max) {
    double value = 0;
    const char* end = text.data() + text.size();
    auto [stop, error] = std::from_chars(text.data(), end, value, std::chars_format::general);
    if (text.empty() || stop != end || (error != std::errc{} && error != std::errc::result_out_of_range))
        return fail(fmt::format("'{}' is not a number", shown_text(text, 80)));
    if (error != std::errc{} || !std::isfinite(value) || !(float(value) > 0) || value > max)
        return fail(fmt::format("'{}' is not a number above 0 and at most {}", shown_text(text, 80), max));
    return float(value);
}

// What the resolve lines read so far: each key's value, and the line that gave it.
struct ResolveLines {
    ResolveSettings settings{1, 0.1f, ColorMapKind::linear, 1, HistoryFilter::bilinear, false};
    std::map<std::string_view, int> given; // key, line number

    // `key: value` on line `number`, `where` naming it.
    Result<void> read(std::string_view key, std::string_view value, int number, const std::string& where) {
        auto known = std::ranges::find(kResolveKeys, key);
        const auto upscale_key = std::ranges::find(kUpscaleKeys, key);
        if (known == std::end(kResolveKeys) && upscale_key == std::end(kUpscaleKeys))
            return fail(fmt::format("{}: unknown key '{}'; a line is a variant name, `set: FILE`, or one of the "
                                    "resolve's settings (gamma:, current-weight:, color-map:, history-filter:, "
                                    "dilate-motion:, and for an upscaling resolve upscale-filter:, "
                                    "upscale-sample-distance:, upscale-box-scale:)",
                                    where, shown_text(key, 80)));
        const std::string_view name = known != std::end(kResolveKeys) ? *known : *upscale_key;
        if (auto earlier = given.find(name); earlier != given.end())
            return fail(fmt::format("{}: '{}:' is given twice (first on line {})", where, key, earlier->second));
        given.emplace(name, number);
        auto refused = [&](const std::string& why) { return fail(fmt::format("{}: {}: {}", where, key, why)); };
        auto parsed = [&](auto parse, auto& into) -> Result<void> {
            auto value_read = parse(value);
            if (!value_read) return refused(shown_text(value_read.error().message, 300));
            into = *value_read;
            return {};
        };
        if (key == "upscale-filter") return parsed(parse_upscale_filter, settings.upscale_filter);
        if (key == "upscale-sample-distance") return parsed(parse_sample_distance, settings.sample_distance);
        if (key == "upscale-box-scale") return parsed(parse_box_scale, settings.box_scale);
        if (key == "gamma" || key == "current-weight") {
            auto number_read = positive_float(value, key == "gamma" ? 100 : 1);
            if (!number_read) return refused(number_read.error().message);
            (key == "gamma" ? settings.gamma : settings.current_weight) = *number_read;
        } else if (key == "color-map") {
            auto map = parse_color_map(value);
            if (!map) return refused(shown_text(map.error().message, 300));
            settings.color_map = map->kind == ColorMap::Kind::power ? ColorMapKind::power
                                 : map->kind == ColorMap::Kind::log ? ColorMapKind::log
                                                                    : ColorMapKind::linear;
            settings.color_map_exponent = map->kind == ColorMap::Kind::power ? map->exponent : 1.0;
        } else if (key == "history-filter") {
            if (value == to_string(HistoryFilter::bilinear))
                settings.history_filter = HistoryFilter::bilinear;
            else if (value == to_string(HistoryFilter::catmull_rom))
                settings.history_filter = HistoryFilter::catmull_rom;
            else
                return refused(
                    fmt::format("'{}' is not a history filter; use bilinear or catmull-rom", shown_text(value, 80)));
        } else if (value == "yes" || value == "no") {
            settings.dilate_motion = value == "yes";
        } else {
            return refused(fmt::format("'{}' is neither yes nor no", shown_text(value, 80)));
        }
        return {};
    }

    // All five or none; and the upscaling resolve's three all or none, and only with the five.
    Result<std::optional<ResolveSettings>> finish(const fs::path& path) {
        if (given.empty()) return std::optional<ResolveSettings>();
        std::vector<std::string_view> missing, missing_upscale;
        for (std::string_view key : kResolveKeys)
            if (!given.count(key)) missing.push_back(key);
        for (std::string_view key : kUpscaleKeys)
            if (!given.count(key)) missing_upscale.push_back(key);
        if (!missing_upscale.empty() && missing_upscale.size() < std::size(kUpscaleKeys))
            return fail(fmt::format("{}: records how its resolve upscaled but not {}: a manifest records all three "
                                    "(upscale-filter:, upscale-sample-distance:, upscale-box-scale:) or none",
                                    path.string(), fmt::join(missing_upscale, ", ")));
        settings.upscaling = missing_upscale.empty();
        if (!missing.empty())
            return fail(fmt::format("{}: records its resolve's settings but not {}: a manifest records all five "
                                    "(gamma:, current-weight:, color-map:, history-filter:, dilate-motion:) or none, "
                                    "so none is left to a guess",
                                    path.string(), fmt::join(missing, ", ")));
        return std::optional(settings);
    }
};

} // namespace

std::string color_map_text(const ResolveSettings& resolve) {
    ColorMap map;
    map.kind = resolve.color_map == ColorMapKind::power ? ColorMap::Kind::power
               : resolve.color_map == ColorMapKind::log ? ColorMap::Kind::log
                                                        : ColorMap::Kind::linear;
    map.exponent = resolve.color_map_exponent;
    return to_string(map);
}

std::string resolve_lines(const ResolveSettings& resolve) {
    std::string lines =
        fmt::format("gamma: {}\ncurrent-weight: {}\ncolor-map: {}\nhistory-filter: {}\ndilate-motion: {}\n",
                    resolve.gamma, resolve.current_weight, color_map_text(resolve), to_string(resolve.history_filter),
                    resolve.dilate_motion ? "yes" : "no");
    if (resolve.upscaling)
        lines += fmt::format("upscale-filter: {}\nupscale-sample-distance: {}\nupscale-box-scale: {}\n",
                             to_string(resolve.upscale_filter), to_string(resolve.sample_distance),
                             to_string(resolve.box_scale));
    return lines;
}

Result<Manifest> read_manifest(const fs::path& path) {
    auto content = read_input_file(path);
    if (!content) return fail(fmt::format("{} (the manifest)", content.error().message));
    std::string_view rest = *content;
    if (rest.starts_with("\xEF\xBB\xBF")) rest.remove_prefix(3); // a UTF-8 byte-order mark some editors write
    Manifest manifest;
    std::map<std::string, AxisSet> declared; // `set:` files by set name
    ResolveLines resolve;
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
        // No variant name holds a colon: any other `key: value` line is one of the resolve's.
        if (const std::size_t colon = line.find(':'); colon != std::string_view::npos) {
            if (auto ok = resolve.read(trimmed(line.substr(0, colon)), trimmed(line.substr(colon + 1)), number, where);
                !ok)
                return std::unexpected(ok.error());
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
    auto settings = resolve.finish(path);
    if (!settings) return std::unexpected(settings.error());
    manifest.resolve = *settings;
    return manifest;
}

} // namespace kdop
