// libFuzzer target: any bytes as an output folder's listing (core/output_listing.h), the file a
// run reads to know which files of an earlier run to remove. Whatever is refused must be refused
// with a message that names the listing, holds no raw control bytes and stays short; whatever is
// read must be paths that stay inside the folder, and must read back the same once written again.
// Any violation aborts, which libFuzzer reports.
#include "core/output_listing.h"
#include "tests/fuzz/fuzz_checks.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>

using kdop::fuzz::has_control_bytes;
using kdop::fuzz::require;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size), origin = "out/.kdop-outputs";
    auto listed = kdop::parse_output_listing(text, origin);
    if (!listed) {
        const std::string& message = listed.error().message;
        require(message.rfind(origin + ":", 0) == 0, "an error that does not name the listing and line", message);
        require(!has_control_bytes(message), "an error that echoes control bytes", message);
        require(message.size() < 2000, "an error that repeats a long line whole", message);
        return 0;
    }
    const std::filesystem::path folder = "/out";
    for (const std::string& entry : *listed) {
        require(!has_control_bytes(entry), "an entry with a control byte", entry);
        const std::filesystem::path inside = (folder / entry).lexically_normal();
        const auto relative = inside.lexically_relative(folder);
        require(!relative.empty() && *relative.begin() != ".." && *relative.begin() != ".",
                "an entry that leaves the folder", entry);
    }
    auto again = kdop::parse_output_listing(kdop::output_listing_text(*listed), origin);
    require(bool(again), "a listing kdop wrote that it cannot read", text);
    std::vector<std::string> sorted = *listed;
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    require(*again == sorted, "a listing that reads back different", text);
    return 0;
}
