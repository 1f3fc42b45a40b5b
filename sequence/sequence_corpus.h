// What a --sequence argument names, for a corpus of many sequences (a studio's captures): a
// sequence's folder (with sequence.json) stands for itself; a folder of sequences (no
// sequence.json of its own, subfolders that have one) for each of them, in byte order of their
// names; a list file for the folders its lines name. An NSS capture's root holds many sequences
// (NNNN.json): nss_sequences() lists them.
#pragma once

#include "core/result.h"

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

// A list file's folders: one per line, relative to the list's own folder unless absolute; a blank
// line or one starting with # is skipped; a line's trailing \r (a list saved on Windows) is not
// part of its name. Refused, naming the file and line: a line holding a NUL; a list with no
// folder. `file` is the list's path as given, which messages name.
Result<std::vector<std::string>> parse_sequence_list(std::string_view text, const std::filesystem::path& file);

// Every sequence folder `given` names (see above), in order, each once as given; a folder of
// sequences adds its subfolders', a list file its lines' (each a sequence's folder or a folder of
// sequences, not another list). Refused, naming `option` and the argument: a path that is neither
// a sequence, nor a folder with one, nor a readable list.
Result<std::vector<std::string>> expand_sequence_arguments(std::span<const std::string> given, std::string_view option);

// The sequences of an NSS capture's root: the NNNN of each NNNN.json there (four digits or
// more), in numeric order. Refused where there is none.
Result<std::vector<std::string>> nss_sequences(const std::filesystem::path& root);

} // namespace kdop
