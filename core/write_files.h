// Writing a command's outputs as a set, all or nothing: every file is first written next to its
// destination under a temporary name unique to this process, and only when all of them are
// complete are they moved into place; each file they replace keeps a second name until the whole
// set is in place. A failure at any step, or SIGINT/SIGTERM (core/interrupt.h), puts the previous
// files back, removes the temporaries and the folders made for the set: the destination is left
// as it was, and two processes writing the same outputs never share a temporary. Before anything
// is written, a destination that is a folder, a special file (a device, a FIFO, a socket: renaming
// over /dev/null would replace the device with a regular file) or an input of this run
// (core/input_files.h) is refused. A writer that throws (out of memory inside an image library)
// is undone the same way, and its exception goes on.
//
// A file whose new content equals what is already there is left untouched, time stamp included, so
// regenerating an unchanged output (kdop_add_variants() after an axis file was touched) makes a
// build system recompile nothing that includes it.
#pragma once

#include "core/result.h"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace kdop {

struct OutputFile {
    std::filesystem::path path;
    std::string content; // bytes, written as is
};

Result<void> write_files_atomically(const std::vector<OutputFile>& files);

// The same for files another library writes (an image writer): `write` is given the temporary
// path to write to and reports failure as an error that names `path`.
struct OutputWriter {
    std::filesystem::path path;
    std::function<Result<void>(const std::filesystem::path& temporary)> write;
};
// `stale`: files of an earlier set that this one replaces as a whole (core/output_listing.h).
// They are moved aside as the set moves into place, put back if it fails or is interrupted, and
// removed with the files the set replaced once it is in place.
Result<void> write_atomically(const std::vector<OutputWriter>& files,
                              const std::vector<std::filesystem::path>& stale = {});

// The writer of `file`'s bytes (what write_files_atomically writes), for a set that mixes them with
// files other libraries write. It refers to `file`, which must outlive the write.
OutputWriter content_writer(const OutputFile& file);

// The temporary a file is written under before it is renamed to `path`: next to it, unique to
// this process and call, keeping the extension (which tells image libraries the format).
std::filesystem::path temporary_path_for(const std::filesystem::path& path);

// Whether files can be written into `dir` (created later, by write_files_atomically, if missing):
// its nearest existing ancestor must be a directory this process can create files in. Checked
// before a long run starts, so a bad --out fails at once instead of after the work. Creates
// nothing. Errors name `option` and the path.
Result<void> check_output_directory(const std::filesystem::path& dir, const std::string& option = "--out");

// Whether `path` can be written as an output file: it is not a folder, and where it exists it is a
// regular file (or a link to one), never a device, FIFO or socket; its folder passes
// check_output_directory. What a command checks for each output file its command line names,
// before the work. Errors name `option` and the path.
Result<void> check_output_file(const std::filesystem::path& path, const std::string& option);

// What `path` is when it exists and is neither a regular file nor a folder ("a character device",
// "a FIFO", ...), following links; nullopt otherwise.
std::optional<std::string> special_file_kind(const std::filesystem::path& path);

} // namespace kdop
