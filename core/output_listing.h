// The listing an output folder keeps of the files the last kdop run wrote into it, so that a folder
// holds one run's outputs: the next run into it removes, with its own set and as part of it, every
// listed file it does not write again (an old kdop.manifest after a choose that recommends nothing,
// the charts of a sequence no longer measured, the viewer's frames of a larger --viewer-frames).
// Files kdop did not write are never listed and never touched.
//
// The listing is `.kdop-outputs` in the folder: a comment line, then each file's path relative to
// the folder, one per line, sorted (the same set gives the same bytes). It is written last of the
// set. A listing is input from a file anyone may edit, so each entry must be a plain relative path
// inside the folder; removal follows no link (see stale_outputs()).
#pragma once

#include "core/result.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

inline constexpr std::string_view kOutputListingName = ".kdop-outputs";

// The listing's text for `files`, paths relative to the folder (any order; written sorted; one
// that is not a plain relative path inside the folder is left out).
std::string output_listing_text(std::vector<std::string> files);

// The entries of a listing's `text`, read from `origin` (for messages). Fails naming origin:line for
// an entry that is not a relative path inside the folder: absolute, with an empty, "." or ".."
// component, or holding a control byte.
Result<std::vector<std::string>> parse_output_listing(std::string_view text, const std::string& origin);

// The listing in `dir`, or none where the folder has no listing (a new folder, or one no kdop run
// wrote). Fails naming the listing where it cannot be read or parsed.
Result<std::vector<std::string>> read_output_listing(const std::filesystem::path& dir);

// Of `listed` (a listing's entries), the files to remove from `dir` with a set that writes `kept`
// (relative paths): those not kept that are still regular files reached through real folders inside
// `dir` (an entry whose file or folder has been replaced by a link is left alone, so no link can
// lead a removal outside --out) and are not inputs of this run (core/input_files.h).
std::vector<std::filesystem::path> stale_outputs(const std::filesystem::path& dir,
                                                 const std::vector<std::string>& listed,
                                                 const std::vector<std::string>& kept);

} // namespace kdop
