// A table declared as columns with their getters: each column's name, unit and how it is shown
// beside the one line that reads its value from a row, so a new metric is one declaration next to
// its computation and a column cannot be paired with another column's value.
#pragma once

#include "core/variant_key.h"
#include "harness/table.h"

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace kdop {

template <class Row>
struct DeclaredColumn {
    Column column;
    std::function<Value(const Row&)> value;
};

template <class Row>
using DeclaredColumns = std::vector<DeclaredColumn<Row>>;

// The table of `rows` under `columns`, in their order.
template <class Row>
Table declared_table(const DeclaredColumns<Row>& columns, std::span<const Row> rows) {
    std::vector<Column> header;
    for (const DeclaredColumn<Row>& c : columns) header.push_back(c.column);
    Table table(std::move(header));
    for (const Row& row : rows) {
        std::vector<Value> values;
        for (const DeclaredColumn<Row>& c : columns) values.push_back(c.value(row));
        table.add(std::move(values));
    }
    return table;
}

// The columns naming a row's variant (variant, axis_set, mode, neighborhood; the baseline `copy`
// has no neighborhood), read through `key`.
template <class Row>
DeclaredColumns<Row> variant_key_columns(std::function<const VariantKey&(const Row&)> key) {
    return {{{"variant", "", Shown::text}, [key](const Row& r) { return Value(key(r).name()); }},
            {{"axis_set", "", Shown::text},
             [key](const Row& r) { return Value(key(r).mode == Mode::shader ? std::string() : key(r).set); }},
            {{"mode", "", Shown::text}, [key](const Row& r) { return Value(std::string(to_string(key(r).mode))); }},
            {{"neighborhood", "", Shown::text}, [key](const Row& r) {
                 const VariantKey& k = key(r);
                 const bool none = k.mode == Mode::copy || k.mode == Mode::shader;
                 return Value(none ? std::string() : std::string(to_string(k.neighborhood)));
             }}};
}

// A time's median and quartiles over interleaved rounds (ms, ms_q1, ms_q3), read from those members.
template <class Row>
DeclaredColumns<Row> time_columns(double Row::*ms, double Row::*q1, double Row::*q3) {
    return {{{"ms", "ms", Shown::fixed, 3, "median"}, [ms](const Row& r) { return maybe(r.*ms); }},
            {{"ms_q1", "ms", Shown::fixed, 3, "Q1"}, [q1](const Row& r) { return maybe(r.*q1); }},
            {{"ms_q3", "ms", Shown::fixed, 3, "Q3"}, [q3](const Row& r) { return maybe(r.*q3); }}};
}

// `a`, then `b`.
template <class Row>
DeclaredColumns<Row> operator+(DeclaredColumns<Row> a, const DeclaredColumns<Row>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

} // namespace kdop
