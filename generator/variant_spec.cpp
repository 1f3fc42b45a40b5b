#include "variant_spec.h"

#include "embedded_files.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <sstream>

namespace kdop {
namespace {

constexpr std::string_view kDefaultSets[] = {"aabb", "ycocg", "dop16-grass", "dop16-asphalt", "dop22", "dop32"};

constexpr glm::ivec2 kOffsetsN9[] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {0, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};
constexpr glm::ivec2 kOffsetsN5[] = {{0, -1}, {-1, 0}, {0, 0}, {1, 0}, {0, 1}};

std::string builtin_path(std::string_view name) { return fmt::format("shader_templates/axis_sets/{}.axes", name); }

template <class T>
bool contains(std::span<const T> list, const T& value) {
    return std::find(list.begin(), list.end(), value) != list.end();
}

// Parses option values naming enum choices; no values means all of them.
template <class T>
Result<std::vector<T>> parse_choices(const std::vector<std::string>& args, std::string_view option, std::string_view what,
                                     std::string_view expected, std::optional<T> (*parse)(std::string_view),
                                     std::span<const T> all) {
    std::vector<T> choices;
    for (const std::string& arg : args) {
        auto choice = parse(arg);
        if (!choice) return fail(fmt::format("{}: unknown {} '{}' (expected {})", option, what, arg, expected));
        if (contains<T>(choices, *choice)) return fail(fmt::format("{}: '{}' is given twice", option, arg));
        choices.push_back(*choice);
    }
    if (choices.empty()) choices.assign(all.begin(), all.end());
    return choices;
}

} // namespace

std::string variant_name(const VariantSpec& spec) {
    if (spec.mode == Mode::copy) return "copy";
    if (spec.mode == Mode::gather) return fmt::format("gather-{}", to_string(spec.neighborhood));
    return fmt::format("{}-{}-{}{}{}", spec.set.name, to_string(spec.mode), to_string(spec.neighborhood),
                       spec.form == Form::loop ? "-loop" : "",
                       spec.style.numerics == EmitStyle::Numerics::paper ? "-paper" : "");
}

std::vector<VariantSpec> baseline_kernels() {
    return {{{}, Mode::gather, Neighborhood::n9}, {{}, Mode::gather, Neighborhood::n5}, {{}, Mode::copy, Neighborhood::n9}};
}

std::vector<VariantSpec> all_builtin_variants() {
    std::vector<VariantSpec> specs = *select_variants({}, {}, {}, {"unrolled", "loop"}); // built-in: cannot fail
    for (VariantSpec& b : baseline_kernels()) specs.push_back(std::move(b));
    return specs;
}

std::optional<Form> parse_form(std::string_view s) {
    for (Form f : {Form::unrolled, Form::loop})
        if (s == to_string(f)) return f;
    return std::nullopt;
}

std::span<const glm::ivec2> neighborhood_offsets(Neighborhood n) {
    if (n == Neighborhood::n9) return kOffsetsN9;
    return kOffsetsN5;
}

int neighborhood_center(Neighborhood n) { return n == Neighborhood::n9 ? 4 : 2; }

std::optional<Mode> parse_mode(std::string_view s) {
    for (Mode m : kAllModes)
        if (s == to_string(m)) return m;
    return std::nullopt;
}

std::optional<Neighborhood> parse_neighborhood(std::string_view s) {
    for (Neighborhood n : kAllNeighborhoods)
        if (s == to_string(n)) return n;
    return std::nullopt;
}

std::span<const std::string_view> default_set_names() { return kDefaultSets; }

Result<AxisSet> resolve_axis_set(std::string_view name_or_path) {
    if (contains(default_set_names(), name_or_path)) {
        std::string path = builtin_path(name_or_path);
        auto text = find_embedded_file(path);
        if (!text) return fail(fmt::format("internal error: built-in axis set '{}' is not embedded", path));
        return parse_axis_set(*text, path);
    }
    std::ifstream file{std::string(name_or_path), std::ios::binary};
    if (!file)
        return fail(fmt::format("--sets: '{}' is not a built-in axis set ({}) nor a readable file",
                                name_or_path, fmt::join(default_set_names(), ", ")));
    std::ostringstream text;
    text << file.rdbuf();
    if (file.bad()) return fail(fmt::format("{}: read error", name_or_path));
    return parse_axis_set(text.str(), name_or_path);
}

Result<std::vector<VariantSpec>> select_variants(const std::vector<std::string>& set_args,
                                                 const std::vector<std::string>& mode_args,
                                                 const std::vector<std::string>& neighborhood_args,
                                                 const std::vector<std::string>& form_args) {
    std::vector<std::string> set_names(set_args.begin(), set_args.end());
    if (set_names.empty()) set_names.assign(kDefaultSets, kDefaultSets + std::size(kDefaultSets));

    std::vector<AxisSet> sets;
    for (const std::string& arg : set_names) {
        auto set = resolve_axis_set(arg);
        if (!set) return std::unexpected(set.error());
        for (const AxisSet& other : sets)
            if (other.name == set->name)
                return fail(other.origin == set->origin
                                ? fmt::format("--sets: '{}' is given twice", arg)
                                : fmt::format("--sets: two axis sets are named '{}': {} and {}", set->name, other.origin,
                                              set->origin));
        sets.push_back(std::move(*set));
    }

    auto modes = parse_choices<Mode>(mode_args, "--modes", "mode", "clip or varclip", parse_mode, kAllModes);
    if (!modes) return std::unexpected(modes.error());
    auto neighborhoods = parse_choices<Neighborhood>(neighborhood_args, "--neighborhoods", "neighborhood", "n9 or n5",
                                                     parse_neighborhood, kAllNeighborhoods);
    if (!neighborhoods) return std::unexpected(neighborhoods.error());
    constexpr Form kDefaultForms[] = {Form::unrolled};
    auto forms = parse_choices<Form>(form_args, "--forms", "form", "unrolled or loop", parse_form, kDefaultForms);
    if (!forms) return std::unexpected(forms.error());

    std::vector<VariantSpec> specs;
    for (const AxisSet& set : sets)
        for (Mode mode : *modes)
            for (Neighborhood n : *neighborhoods)
                for (Form form : *forms) specs.push_back({set, mode, n, form});
    return specs;
}

} // namespace kdop
