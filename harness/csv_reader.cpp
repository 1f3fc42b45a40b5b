#include "harness/csv_reader.h"

#include "core/read_file.h"

#include <fmt/format.h>

#include <algorithm>

namespace kdop {

int CsvFile::column(std::string_view name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    return it == header.end() ? -1 : static_cast<int>(it - header.begin());
}

Result<CsvFile> parse_csv(std::string_view text, std::string_view origin) {
    CsvFile csv;
    csv.origin = std::string(origin);
    std::vector<std::vector<std::string>> records;
    std::vector<int> starts;
    std::vector<std::string> record;
    std::string field;
    bool quoted = false, field_started = false;
    int line = 1, record_line = 1;
    auto end_field = [&] {
        record.push_back(std::move(field));
        field.clear();
        field_started = false;
    };
    auto end_record = [&] {
        end_field();
        if (!(record.size() == 1 && record[0].empty())) { // blank lines are skipped
            records.push_back(std::move(record));
            starts.push_back(record_line);
        }
        record.clear();
    };
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                field += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                line += c == '\n';
                field += c;
            }
        } else if (c == '"' && !field_started) {
            quoted = field_started = true;
        } else if (c == ',') {
            end_field();
        } else if (c == '\n' || c == '\r') {
            if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
            end_record();
            record_line = ++line;
        } else {
            field += c;
            field_started = true;
        }
    }
    if (quoted) return fail(fmt::format("{}:{}: a quoted field is not closed", origin, record_line));
    if (!field.empty() || !record.empty()) end_record();
    if (records.empty()) return fail(fmt::format("{}:1: empty; expected a header line", origin));
    csv.header = std::move(records.front());
    for (std::size_t r = 1; r < records.size(); ++r) {
        if (records[r].size() != csv.header.size())
            return fail(fmt::format("{}:{}: {} fields, the header has {}", origin, starts[r], records[r].size(),
                                    csv.header.size()));
        csv.rows.push_back(std::move(records[r]));
        csv.lines.push_back(starts[r]);
    }
    return csv;
}

Result<CsvFile> read_csv(const std::filesystem::path& path) {
    auto text = read_file(path);
    if (!text) return fail(fmt::format("{}: cannot read", path.string()));
    return parse_csv(*text, path.string());
}

} // namespace kdop
