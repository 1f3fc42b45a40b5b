#include "generator/variant_spec.h"

#include "core/builtin_sets.h"
#include "core/read_file.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>

namespace kdop {
namespace {

constexpr glm::ivec2 kOffsetsN9[] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {0, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};
constexpr glm::ivec2 kOffsetsN5[] = {{0, -1}, {-1, 0}, {0, 0}, {1, 0}, {0, 1}};

template <class T>
bool contains(std::span<const T> list, const T& value) {
    return std::find(list.begin(), list.end(), value) != list.end();
}

// Parses option values naming enum choices; no values means all of them.
template <class T>
Result<std::vector<T>> parse_choices(const std::vector<std::string>& args, std::string_view option,
                                     std::string_view what, std::string_view expected,
                                     std::optional<T> (*parse)(std::string_view), std::span<const T> all) {
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

std::string default_modes_text(const SelectionDefaults& defaults) {
    std::vector<std::string> names;
    for (Mode mode : defaults.modes) names.push_back(to_string(mode));
    return fmt::format("{}", fmt::join(names, " "));
}

std::string default_neighborhoods_text(const SelectionDefaults& defaults) {
    std::vector<std::string> names;
    for (Neighborhood n : defaults.neighborhoods) names.push_back(to_string(n));
    return fmt::format("{}", fmt::join(names, " "));
}

std::vector<VariantKey> keys_of(const std::vector<VariantSpec>& specs) {
    std::vector<VariantKey> keys;
    for (const VariantSpec& spec : specs) keys.push_back(spec.key());
    return keys;
}

std::vector<VariantSpec> baseline_kernels() {
    return {
        {{}, Mode::gather, Neighborhood::n9}, {{}, Mode::gather, Neighborhood::n5}, {{}, Mode::copy, Neighborhood::n9}};
}

std::vector<VariantSpec> all_builtin_variants() {
    std::vector<VariantSpec> specs = *select_variants({}, {}, {}, {"unrolled", "loop"}); // built-in: cannot fail
    for (VariantSpec& b : baseline_kernels()) specs.push_back(std::move(b));
    return specs;
}

std::span<const glm::ivec2> neighborhood_offsets(Neighborhood n) {
    if (n == Neighborhood::n9) return kOffsetsN9;
    return kOffsetsN5;
}

int neighborhood_center(Neighborhood n) { return n == Neighborhood::n9 ? 4 : 2; }

Result<AxisSet> resolve_axis_set(std::string_view name_or_path) {
    if (auto text = builtin_set_text(name_or_path)) return parse_axis_set(*text, builtin_set_path(name_or_path));
    auto text = read_file(std::string(name_or_path));
    if (!text)
        return fail(fmt::format("--sets: '{}' is not a built-in axis set ({}) nor a readable file", name_or_path,
                                builtin_set_list()));
    return parse_axis_set(*text, name_or_path);
}

Result<std::vector<VariantSpec>> select_variants(const std::vector<std::string>& set_args,
                                                 const std::vector<std::string>& mode_args,
                                                 const std::vector<std::string>& neighborhood_args,
                                                 const std::vector<std::string>& form_args,
                                                 const SelectionDefaults& defaults) {
    std::vector<std::string> set_names(set_args.begin(), set_args.end());
    if (set_names.empty()) set_names.assign(builtin_set_names().begin(), builtin_set_names().end());

    std::vector<AxisSet> sets;
    for (const std::string& arg : set_names) {
        auto set = resolve_axis_set(arg);
        if (!set) return std::unexpected(set.error());
        for (const AxisSet& other : sets)
            if (other.name == set->name)
                return fail(other.origin == set->origin ? fmt::format("--sets: '{}' is given twice", arg)
                                                        : fmt::format("--sets: two axis sets are named '{}': {} and {}",
                                                                      set->name, other.origin, set->origin));
        sets.push_back(std::move(*set));
    }

    auto modes = parse_choices<Mode>(mode_args, "--modes", "mode", "clip or varclip", parse_mode, defaults.modes);
    if (!modes) return std::unexpected(modes.error());
    auto neighborhoods = parse_choices<Neighborhood>(neighborhood_args, "--neighborhoods", "neighborhood", "n9 or n5",
                                                     parse_neighborhood, defaults.neighborhoods);
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
