#include "core/variant_key.h"

#include "core/shown_text.h"

#include <fmt/format.h>

#include <initializer_list>

namespace kdop {

std::string VariantKey::name() const {
    if (mode == Mode::copy) return "copy";
    if (mode == Mode::shader) return set; // a shader of its own is named by its name alone
    if (mode == Mode::gather) return fmt::format("gather-{}", to_string(neighborhood));
    return fmt::format("{}-{}-{}{}{}", set, to_string(mode), to_string(neighborhood), form == Form::loop ? "-loop" : "",
                       numerics == Numerics::paper ? "-paper" : "");
}

VariantKey VariantKey::with(Form f) const {
    VariantKey k = *this;
    k.form = f;
    return k;
}

VariantKey VariantKey::with(Numerics n) const {
    VariantKey k = *this;
    k.numerics = n;
    return k;
}

VariantKey VariantKey::with_set(std::string other) const {
    VariantKey k = *this;
    k.set = std::move(other);
    return k;
}

VariantKey gather_key(Neighborhood n) { return {"", Mode::gather, n, Form::unrolled, Numerics::hardened}; }
VariantKey copy_key() { return {"", Mode::copy, Neighborhood::n9, Form::unrolled, Numerics::hardened}; }

namespace {

// The choice among `all` whose name (to_string) is `s`.
template <class T>
std::optional<T> parse_choice(std::string_view s, std::initializer_list<T> all) {
    for (T choice : all)
        if (s == to_string(choice)) return choice;
    return std::nullopt;
}

} // namespace

std::optional<Mode> parse_mode(std::string_view s) { return parse_choice(s, {Mode::clip, Mode::varclip}); }
std::optional<Neighborhood> parse_neighborhood(std::string_view s) {
    return parse_choice(s, {Neighborhood::n9, Neighborhood::n5});
}
std::optional<Form> parse_form(std::string_view s) { return parse_choice(s, {Form::unrolled, Form::loop}); }
std::optional<Numerics> parse_numerics(std::string_view s) {
    return parse_choice(s, {Numerics::hardened, Numerics::paper});
}

bool is_valid_set_name(std::string_view name) {
    if (name.empty() || name.size() > 48 || !(name[0] >= 'a' && name[0] <= 'z')) return false;
    char previous = 0;
    for (char c : name) {
        bool alnum = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
        if (!alnum && !(c == '-' && previous != '-')) return false;
        previous = c;
    }
    return previous != '-';
}

Result<VariantKey> parse_variant_key(std::string_view name, std::string_view option) {
    if (name == "copy") return copy_key();
    for (Neighborhood n : {Neighborhood::n9, Neighborhood::n5})
        if (name == gather_key(n).name()) return gather_key(n);
    // Suffixes are read from the right, since set names have dashes of their own.
    VariantKey key;
    std::string_view rest = name;
    auto take_suffix = [&](std::string_view suffix) {
        if (!rest.ends_with(suffix)) return false;
        rest.remove_suffix(suffix.size());
        return true;
    };
    if (take_suffix("-paper")) key.numerics = Numerics::paper;
    if (take_suffix("-loop")) key.form = Form::loop;
    auto take_word = [&]() -> std::string_view {
        const auto dash = rest.rfind('-');
        if (dash == std::string_view::npos) return {};
        std::string_view word = rest.substr(dash + 1);
        rest = rest.substr(0, dash);
        return word;
    };
    const auto neighborhood = parse_neighborhood(take_word());
    const auto mode = parse_mode(take_word());
    if (!neighborhood || !mode || !is_valid_set_name(rest))
        return fail(fmt::format("{}: '{}' is not a variant name: expected <set>-<clip|varclip>-<n9|n5>[-loop][-paper], "
                                "gather-n9, gather-n5 or copy (see `kdop list --all`)",
                                option, shown_text(name)));
    key.set = std::string(rest);
    key.mode = *mode;
    key.neighborhood = *neighborhood;
    return key;
}

} // namespace kdop
