// A table printed as fixed-width text (on a terminal, in an axis file's comments), declared as
// columns with their getters as declared_table.h declares the tables written as files: each
// column's header and width beside the one line that writes its cell from a row. Rows can be
// printed one at a time, as they are computed.
#pragma once

#include <fmt/format.h>

#include <functional>
#include <string>
#include <vector>

namespace kdop {

template <class Row>
struct PrintedColumn {
    std::string header;
    int width = 0; // the cell right-aligned in it; negative: left-aligned
    std::function<std::string(const Row&)> cell;
    std::string separator = " "; // before the column, unless it is the first
};

template <class Row>
using PrintedColumns = std::vector<PrintedColumn<Row>>;

namespace printed_detail {

template <class Row, class Text>
std::string line(const PrintedColumns<Row>& columns, Text&& text) {
    std::string out;
    for (std::size_t i = 0; i < columns.size(); ++i) {
        const PrintedColumn<Row>& c = columns[i];
        if (i > 0) out += c.separator;
        out += c.width < 0 ? fmt::format("{:<{}}", text(c), -c.width) : fmt::format("{:>{}}", text(c), c.width);
    }
    return out;
}

} // namespace printed_detail

// `a`, then `b`.
template <class Row>
PrintedColumns<Row> operator+(PrintedColumns<Row> a, const PrintedColumns<Row>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

template <class Row>
std::string printed_header(const PrintedColumns<Row>& columns) {
    return printed_detail::line(columns, [](const PrintedColumn<Row>& c) { return c.header; });
}

template <class Row>
std::string printed_row(const PrintedColumns<Row>& columns, const Row& row) {
    return printed_detail::line(columns, [&row](const PrintedColumn<Row>& c) { return c.cell(row); });
}

} // namespace kdop
