// The identity of a variant: axis set, mode, neighborhood, form and numerics. Every command, the
// registry and every report row name variants through this key, never by building or cutting
// strings, so a user's own set, a loop form and a paper twin are all measured the same way.
//
// Names: "<set>-<mode>-<neighborhood>[-loop][-paper]" ("dop16-grass-varclip-n5-loop"), and the
// cost baselines "gather-n9", "gather-n5" and "copy", which have no set.
#pragma once

#include "core/result.h"

#include <kdop/variant.h>

#include <compare>
#include <optional>
#include <string>
#include <string_view>

namespace kdop {

struct VariantKey {
    std::string set; // axis-set name; empty for the gather and copy baselines; a Mode::shader's own name
    Mode mode = Mode::clip;
    Neighborhood neighborhood = Neighborhood::n9;
    Form form = Form::unrolled;
    Numerics numerics = Numerics::hardened;

    std::string name() const;
    bool is_clip() const { return mode == Mode::clip || mode == Mode::varclip; }

    // The same variant in another form or with other numerics: its loop-form baseline, its paper twin.
    VariantKey with(Form f) const;
    VariantKey with(Numerics n) const;
    // The same mode, neighborhood, form and numerics with another set, e.g. the RGB AABB to compare with.
    VariantKey with_set(std::string other) const;

    friend auto operator<=>(const VariantKey&, const VariantKey&) = default;
};

// The gather-only baseline of a neighborhood: the same loads and store as its clips, no clip.
VariantKey gather_key(Neighborhood n);
VariantKey copy_key();

// Parses a variant name; the error names `option` and says what was expected.
Result<VariantKey> parse_variant_key(std::string_view name, std::string_view option = "--variant");

std::optional<Mode> parse_mode(std::string_view s);                 // clip, varclip
std::optional<Neighborhood> parse_neighborhood(std::string_view s); // n9, n5
std::optional<Form> parse_form(std::string_view s);                 // unrolled, loop
std::optional<Numerics> parse_numerics(std::string_view s);         // hardened, paper

// Whether `name` can name an axis set: lowercase letters and digits, starting with a letter, single
// '-' between words, at most 48 characters.
bool is_valid_set_name(std::string_view name);

} // namespace kdop
