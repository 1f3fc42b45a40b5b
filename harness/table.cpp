#include "harness/table.h"

#include "core/escaped_text.h"
#include "harness/gnuplot.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace kdop {
namespace {

template <class... F>
struct Overloaded : F... {
    using F::operator()...;
};
// Clang 16 (the fuzzers' compiler) deduces no aggregate's template arguments without it.
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

bool missing(const Value& v) {
    return std::holds_alternative<std::monostate>(v) ||
           (std::holds_alternative<double>(v) && std::isnan(std::get<double>(v)));
}

double as_number(const Value& v) {
    if (const auto* d = std::get_if<double>(&v)) return *d;
    if (const auto* i = std::get_if<std::int64_t>(&v)) return double(*i);
    if (const auto* b = std::get_if<bool>(&v)) return *b ? 1.0 : 0.0;
    return std::numeric_limits<double>::quiet_NaN();
}

// Shortest text that reads back to the same double; infinities as "inf" and "-inf".
std::string exact(double d) { return std::isinf(d) ? (d > 0 ? "inf" : "-inf") : fmt::format("{}", d); }

std::string significant(double d, int digits) {
    if (std::isinf(d)) return d > 0 ? "∞" : "−∞";
    // Enough precision to show every integer digit: 1225 stays 1225, not 1.23e+03.
    const double magnitude = std::abs(d);
    const int integer_digits = magnitude >= 1 ? int(std::floor(std::log10(magnitude))) + 1 : 0;
    return fmt::format("{:.{}g}", d, std::max(digits, integer_digits));
}

} // namespace

Table::Table(std::vector<Column> columns) : columns_(std::move(columns)) {}

void Table::add(std::vector<Value> values) {
    if (values.size() != columns_.size())
        throw std::logic_error(fmt::format("table row has {} values for {} columns (first column '{}')", values.size(),
                                           columns_.size(), columns_.empty() ? "" : columns_.front().name));
    rows_.push_back(std::move(values));
}

std::size_t Table::column(std::string_view name) const {
    for (std::size_t i = 0; i < columns_.size(); ++i)
        if (columns_[i].name == name) return i;
    throw std::logic_error(fmt::format("table has no column '{}'", name));
}

double Table::number(std::size_t row, std::string_view name) const { return as_number(rows_.at(row)[column(name)]); }

std::vector<std::size_t> Table::indices(std::span<const std::string> only) const {
    std::vector<std::size_t> out;
    if (only.empty())
        for (std::size_t i = 0; i < columns_.size(); ++i) out.push_back(i);
    for (const std::string& name : only) out.push_back(column(name));
    return out;
}

std::string csv_field(std::string_view text) {
    if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
    std::string out = "\"";
    for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string Table::csv() const {
    std::string out;
    for (std::size_t c = 0; c < columns_.size(); ++c) {
        if (c) out += ',';
        out += csv_field(columns_[c].name);
    }
    out += "\n";
    for (const auto& row : rows_) {
        for (std::size_t c = 0; c < row.size(); ++c) {
            if (c) out += ',';
            if (missing(row[c])) continue;
            out += std::visit(Overloaded{[](std::monostate) { return std::string(); },
                                         [](const std::string& s) { return csv_field(s); },
                                         [](std::int64_t i) { return std::to_string(i); },
                                         [](double d) { return exact(d); },
                                         [](bool b) { return std::string(b ? "1" : "0"); }},
                              row[c]);
        }
        out += "\n";
    }
    return out;
}

std::string Table::shown(std::size_t row, std::size_t c) const {
    const Value& v = rows_.at(row).at(c);
    if (missing(v)) return "–";
    if (const auto* s = std::get_if<std::string>(&v)) return *s;
    if (const auto* b = std::get_if<bool>(&v)) return *b ? "yes" : "no";
    const Column& column = columns_[c];
    if (const auto* i = std::get_if<std::int64_t>(&v);
        i && (column.shown == Shown::integer || column.shown == Shown::text))
        return std::to_string(*i);
    return format_value(as_number(v), column.shown, column.digits);
}

std::string format_value(double d, Shown shown, int digits) {
    if (std::isnan(d)) return "–";
    switch (shown) {
    case Shown::text:
    case Shown::integer: return exact(d);
    case Shown::fixed: return std::isfinite(d) ? fmt::format("{:.{}f}", d, digits) : significant(d, 1);
    case Shown::significant: return significant(d, digits);
    case Shown::percent: return std::isfinite(d) ? fmt::format("{:.1f}%", 100 * d) : significant(d, 1);
    case Shown::ratio: return std::isfinite(d) ? fmt::format("{:.{}f}×", d, digits) : significant(d, 1);
    case Shown::flag: return d != 0 ? "yes" : "no";
    }
    return exact(d);
}

std::string Table::markdown(std::span<const std::string> only) const {
    const std::vector<std::size_t> shown_columns = indices(only);
    std::string header = "|", rule = "|";
    for (std::size_t c : shown_columns) {
        const Column& column = columns_[c];
        const std::string title = column.title.empty() ? column.name : column.title;
        header += fmt::format(" {}{} |", markdown_text(title), column.unit.empty() ? "" : " (" + column.unit + ")");
        const bool text = column.shown == Shown::text || column.shown == Shown::flag;
        rule += text ? "---|" : "--:|";
    }
    std::string out = header + "\n" + rule + "\n";
    for (std::size_t r = 0; r < rows_.size(); ++r) {
        out += "|";
        for (std::size_t c : shown_columns) out += fmt::format(" {} |", markdown_text(shown(r, c)));
        out += "\n";
    }
    return out;
}

std::string Table::gnuplot(std::span<const std::string> only) const {
    const std::vector<std::size_t> shown_columns = indices(only);
    std::string out;
    for (const auto& row : rows_) {
        for (std::size_t i = 0; i < shown_columns.size(); ++i) {
            const Value& v = row[shown_columns[i]];
            std::string field;
            if (const auto* s = std::get_if<std::string>(&v)) {
                field = "\"";
                for (char ch : *s) field += ch == '"' ? '\'' : ch;
                field += "\"";
            } else {
                field = gnuplot_number(as_number(v));
            }
            if (i) out += ' ';
            out += field;
        }
        out += "\n";
    }
    return out;
}

nlohmann::json Table::json() const {
    nlohmann::json columns = nlohmann::json::array(), rows = nlohmann::json::array();
    for (const Column& c : columns_) columns.push_back({{"name", c.name}, {"unit", c.unit}});
    for (const auto& row : rows_) {
        nlohmann::json object = nlohmann::json::object();
        for (std::size_t c = 0; c < row.size(); ++c) {
            const Value& v = row[c];
            nlohmann::json& field = object[columns_[c].name];
            if (missing(v))
                field = nullptr;
            else if (const auto* s = std::get_if<std::string>(&v))
                field = *s;
            else if (const auto* i = std::get_if<std::int64_t>(&v))
                field = *i;
            else if (const auto* b = std::get_if<bool>(&v))
                field = *b;
            else if (const double d = std::get<double>(v); std::isinf(d))
                field = d > 0 ? "inf" : "-inf"; // JSON has no infinity; a PSNR of identical frames is one
            else
                field = std::isfinite(d) ? nlohmann::json(d) : nlohmann::json(nullptr);
        }
        rows.push_back(std::move(object));
    }
    return {{"columns", std::move(columns)}, {"rows", std::move(rows)}};
}

} // namespace kdop
