// The columns that name a variant in every result table (variant, axis_set, mode, neighborhood),
// declared once with the values a variant has in them, so no two tables spell them differently.
#pragma once

#include "table.h"
#include "variant_key.h"

#include <string>
#include <vector>

namespace kdop {

inline std::vector<Column> variant_columns() {
    return {{"variant", "", Shown::text},
            {"axis_set", "", Shown::text},
            {"mode", "", Shown::text},
            {"neighborhood", "", Shown::text}};
}

// The baseline `copy` has no neighborhood: empty there.
inline std::vector<Value> variant_values(const VariantKey& key) {
    return {key.name(), key.set, std::string(to_string(key.mode)),
            key.mode == Mode::copy ? std::string() : std::string(to_string(key.neighborhood))};
}

// `a`, then `b`: a table's columns or a row's values from their parts.
template <class T>
std::vector<T> joined(std::vector<T> a, const std::vector<T>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

} // namespace kdop
