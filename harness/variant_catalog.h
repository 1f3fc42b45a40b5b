// Every variant by its key, for every command that runs or measures one: the embedded registry's
// entry where it has one (what ships: the built-in sets' hardened variants in both forms, and the
// gather and copy baselines), otherwise built in-process (a user's axis set, any paper twin). So
// `run`, `bench`, `stress`, `accuracy` and `show` accept the same variants, a user's set gets its
// loop form and paper twin like a built-in one, and no command builds names by hand.
//
// Built variants live as long as the catalog; the pointers it hands out stay valid that long.
#pragma once

#include "core/result.h"
#include "core/variant_key.h"
#include "generator/axis_set.h"
#include "generator/runnable_variant.h"
#include "generator/variant_spec.h"

#include <kdop/variant.h>

#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

class VariantCatalog {
public:
    // `sets`: what a --sets option gave: built-in names (nothing to add) and axis-set files, whose
    // sets become known by their `name:`. Errors name the file and line, or the clash of two names.
    // `style`: how built variants are written (`kdop stress --projection ...`); with any but the
    // default, every variant is built, none taken from the registry.
    static Result<VariantCatalog> create(const std::vector<std::string>& sets, const EmitStyle& style = {});

    // The set called `name`: built-in, or from a file given to create(). The error names `option`
    // and says how to make a user's set known.
    Result<AxisSet> set(std::string_view name, std::string_view option) const;

    // What the generator, the reference and the volumes need to know of `key`: its set's axes and
    // this catalog's style.
    Result<VariantSpec> spec(const VariantKey& key, std::string_view option) const;

    // The variant of `key`, built if the registry lacks it.
    Result<const Variant*> find(const VariantKey& key, std::string_view option = "--variant");
    // Several at once; those that need building are built in parallel. Same order as `keys`.
    Result<std::vector<const Variant*>> find_all(std::span<const VariantKey> keys, std::string_view option);

    // Whether `variant` is the embedded registry's (so another process can find it by name).
    static bool is_embedded(const Variant& variant);

    // The keys of every clip variant of the sets given to create() (every built-in set if none), in
    // that order, x modes x neighborhoods, unrolled, with `numerics`: a command's default selection.
    std::vector<VariantKey> clip_keys(Numerics numerics) const;

private:
    // The embedded registry's entry for `key`, or nullptr.
    const Variant* registered(const VariantKey& key) const;

    EmitStyle style_;
    std::vector<AxisSet> user_sets_;
    std::vector<std::string> selected_; // set names in the order given; empty: the built-in sets
    std::map<VariantKey, std::unique_ptr<RunnableVariant>> built_;
};

} // namespace kdop
