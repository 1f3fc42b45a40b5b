// libFuzzer target: any bytes as a list of sequence folders (kdop taa --sequence LIST). Whatever is
// refused must be refused with a message that names the list and its line, holds no raw control
// bytes and stays short; whatever is read is at least one folder, each named relative to the
// list's own folder or absolute, none holding a line break or a NUL. Any violation aborts, which
// libFuzzer reports.
#include "sequence/sequence_corpus.h"
#include "tests/fuzz/fuzz_checks.h"

#include <cstdint>
#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using kdop::fuzz::require;
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    auto folders = kdop::parse_sequence_list(text, "lists/corpus.txt");
    if (!folders) {
        kdop::fuzz::require_refusal_message(folders.error().message, "lists/corpus.txt", "lists/corpus.txt");
        return 0;
    }
    require(!folders->empty(), "a list read as no folder", "");
    for (const std::string& folder : *folders) {
        require(folder.starts_with("lists/") || folder.starts_with("/"), "a folder not under the list's own", folder);
        require(folder.find_first_of(std::string_view("\n\0", 2)) == std::string::npos,
                "a folder with a line break or a NUL", folder);
        require(folder.size() > std::string_view("lists/").size() || folder.starts_with("/"), "an empty folder name",
                folder);
    }
    return 0;
}
