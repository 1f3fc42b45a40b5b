// A result table, declared once per measurement: named columns with their unit and how to show
// them, rows of values, and every format a report needs written from that one declaration: CSV
// (quoted per RFC 4180), Markdown, gnuplot data and JSON. A row with more or fewer values than the
// table has columns is a programming error and throws, so columns and values cannot drift apart.
//
// A value that was not measured is empty (or a NaN double): an empty CSV field, "–" in Markdown,
// NaN in gnuplot data (which gnuplot skips) and null in JSON. Never a made-up zero.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace kdop {

enum class Shown {
    text,        // as is
    integer,     // 1225
    fixed,       // `digits` decimals: 12.35
    significant, // `digits` significant digits, never in exponent form above 1: 0.0372, 1225
    percent,     // a share in [0, 1] as a percentage with one decimal: 18.4%
    ratio,       // `digits` decimals and a times sign: 0.57×
    flag,        // yes / no (1 / 0 in CSV)
};

struct Column {
    std::string name; // the CSV and JSON key: lowercase with underscores, "mean_dist"
    std::string unit; // "ms", "instr/px", "S" (the pixel's magnitude); empty for counts, names and ratios
    Shown shown;
    int digits;
    std::string title; // the Markdown header; empty: the name

    Column(std::string name_, std::string unit_ = "", Shown shown_ = Shown::significant, int digits_ = 3,
           std::string title_ = "")
        : name(std::move(name_)), unit(std::move(unit_)), shown(shown_), digits(digits_), title(std::move(title_)) {}
};

using Value = std::variant<std::monostate, std::string, std::int64_t, double, bool>;

class Table {
public:
    explicit Table(std::vector<Column> columns);

    // Throws std::logic_error when `values` has other than one value per column.
    void add(std::vector<Value> values);

    const std::vector<Column>& columns() const { return columns_; }
    const std::vector<std::vector<Value>>& rows() const { return rows_; }
    // The index of the column called `name`; throws std::logic_error for an unknown name.
    std::size_t column(std::string_view name) const;
    // The same columns with only the rows `keep` accepts (called with the row index).
    template <class Keep>
    Table rows_where(Keep keep) const {
        Table out(columns_);
        for (std::size_t r = 0; r < rows_.size(); ++r)
            if (keep(r)) out.rows_.push_back(rows_[r]);
        return out;
    }
    // A row's number in column `name`; NaN where it is empty or not a number.
    double number(std::size_t row, std::string_view name) const;

    // A header line of column names, then one line per row, '\n'-terminated. Numbers keep every
    // digit (shortest form that reads back exactly); fields with a comma, quote or line break are
    // quoted, quotes doubled.
    std::string csv() const;
    // A Markdown table of `only` (column names, in that order; empty: every column).
    std::string markdown(std::span<const std::string> only = {}) const;
    // Whitespace-separated rows of `only` for gnuplot; text is double-quoted.
    std::string gnuplot(std::span<const std::string> only) const;
    // {"columns": [{"name", "unit"}...], "rows": [{name: value}...]}; an infinite number is the
    // string "inf" or "-inf", a missing one null.
    nlohmann::json json() const;

    // One value as Markdown shows it.
    std::string shown(std::size_t row, std::size_t column) const;

private:
    std::vector<std::size_t> indices(std::span<const std::string> only) const;

    std::vector<Column> columns_;
    std::vector<std::vector<Value>> rows_;
};

// A number as Markdown shows it in a column of that kind: "–" where it is NaN (not measured).
std::string format_value(double value, Shown shown, int digits);

// An optional number: a double where measured, else empty.
inline Value maybe(double value) { return value == value ? Value(value) : Value(); }

// One CSV field, quoted per RFC 4180 where it needs to be.
std::string csv_field(std::string_view text);

} // namespace kdop
