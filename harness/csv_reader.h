// Reading a CSV file that kdop (or a user) wrote: RFC 4180 fields, quoted ones included. Used
// where one command reads another's table, e.g. `kdop accuracy --cost` reading the bench's cost.csv.
#pragma once

#include "core/result.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

struct CsvFile {
    std::string origin; // the path, for messages
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows; // every row has the header's field count
    std::vector<int> lines;                     // the line each row starts on

    // The index of column `name`, or -1.
    int column(std::string_view name) const;
};

// Errors name the file and line: an unterminated quote, a row with another field count than the
// header, an empty file.
Result<CsvFile> parse_csv(std::string_view text, std::string_view origin);
Result<CsvFile> read_csv(const std::filesystem::path& path);

} // namespace kdop
