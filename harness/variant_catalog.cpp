#include "harness/variant_catalog.h"

#include "core/builtin_sets.h"
#include "generator/variant_builder.h"
#include "generator/variant_spec.h"

#include <kdop_builtin_variants.h>

#include <fmt/format.h>

#include <algorithm>

namespace kdop {

Result<VariantCatalog> VariantCatalog::create(const std::vector<std::string>& sets, const EmitStyle& style) {
    VariantCatalog catalog;
    catalog.style_ = style;
    for (const std::string& arg : sets) {
        auto set = resolve_axis_set(arg);
        if (!set) return std::unexpected(set.error());
        if (std::ranges::find(catalog.selected_, set->name) != catalog.selected_.end())
            return fail(fmt::format("--sets: '{}' is given twice, or two files name the set '{}'", arg, set->name));
        catalog.selected_.push_back(set->name);
        if (!is_builtin_set(arg)) {
            if (is_builtin_set(set->name))
                return fail(fmt::format("--sets: {} names its set '{}', the name of a built-in set; rename it", arg,
                                        set->name));
            catalog.user_sets_.push_back(std::move(*set));
        }
    }
    return catalog;
}

Result<AxisSet> VariantCatalog::set(std::string_view name, std::string_view option) const {
    if (is_builtin_set(name)) return resolve_axis_set(name);
    for (const AxisSet& s : user_sets_)
        if (s.name == name) return s;
    return fail(
        fmt::format("{}: no axis set is named '{}': the built-in sets are {}; give a file of yours with --sets FILE",
                    option, name, builtin_set_list()));
}

Result<VariantSpec> VariantCatalog::spec(const VariantKey& key, std::string_view option) const {
    VariantSpec spec{{}, key.mode, key.neighborhood, key.form, key.numerics, style_};
    if (key.is_clip()) {
        auto found = set(key.set, option);
        if (!found) return std::unexpected(found.error());
        spec.set = std::move(*found);
    }
    return spec;
}

bool VariantCatalog::is_embedded(const Variant& variant) {
    for (const Variant& v : builtin::variants())
        if (&v == &variant) return true;
    return false;
}

std::vector<VariantKey> VariantCatalog::clip_keys(Numerics numerics) const {
    std::vector<std::string> sets = selected_;
    if (sets.empty()) sets.assign(builtin_set_names().begin(), builtin_set_names().end());
    std::vector<VariantKey> keys;
    for (const std::string& set : sets)
        for (Mode mode : kAllModes)
            for (Neighborhood n : kAllNeighborhoods) keys.push_back({set, mode, n, Form::unrolled, numerics});
    return keys;
}

const Variant* VariantCatalog::registered(const VariantKey& key) const {
    // The registry holds the built-in sets' variants written in the default style; user sets never
    // take a built-in name (create()), so a registry name is the built-in variant.
    if (!(style_ == EmitStyle{})) return nullptr;
    return builtin::variants().find(key.name().c_str());
}

Result<const Variant*> VariantCatalog::find(const VariantKey& key, std::string_view option) {
    auto found = find_all(std::span(&key, 1), option);
    if (!found) return std::unexpected(found.error());
    return found->front();
}

Result<std::vector<const Variant*>> VariantCatalog::find_all(std::span<const VariantKey> keys,
                                                             std::string_view option) {
    // What the registry lacks is built, all at once (build_variants runs on every core).
    std::vector<VariantSpec> to_build;
    for (const VariantKey& key : keys) {
        if (registered(key) || built_.contains(key)) continue;
        if (std::ranges::any_of(to_build, [&](const VariantSpec& s) { return s.key() == key; })) continue;
        auto spec = this->spec(key, option);
        if (!spec) return std::unexpected(spec.error());
        to_build.push_back(std::move(*spec));
    }
    if (!to_build.empty()) {
        auto built = build_variants(to_build);
        if (!built) return std::unexpected(built.error());
        for (BuiltVariant& b : *built) {
            const VariantKey key = b.spec.key();
            built_.emplace(key, std::make_unique<RunnableVariant>(std::move(b)));
        }
    }
    std::vector<const Variant*> found;
    for (const VariantKey& key : keys) {
        if (auto it = built_.find(key); it != built_.end())
            found.push_back(&it->second->variant());
        else
            found.push_back(builtin::variants().find(key.name().c_str()));
    }
    return found;
}

} // namespace kdop
