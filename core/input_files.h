// The files this process reads, so that no output replaces one: `--out o/in.exr` beside
// `--images o/in.exr`, a link to it, a hard link, `./o/../o/in.exr`. Files are compared by what
// they are (device and inode), never by how they are spelled.
//
// read_file() and read_image() note every file they read; write_atomically() refuses, before it
// writes anything, a destination that is a noted input. That is the last line of defence; a
// command whose outputs are known from its command line checks them against its inputs up front
// too (check_not_an_input), so the refusal comes before the work.
#pragma once

#include "core/result.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

namespace kdop {

// Whether `a` and `b` are the same existing file (false when either does not exist).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

// What a file is, however it is spelled or linked: its device and inode; none when it does not
// exist. For comparing many files at once (same_file compares two).
using FileIdentity = std::pair<std::uint64_t, std::uint64_t>;
std::optional<FileIdentity> file_identity(const std::filesystem::path& path);

// Turns the noting on for the rest of the process (kdop's programs, in run_command_line: one
// process, one run), or off, forgetting what was noted. Off by default, so that a process that
// runs many cases (the test binary) never takes a later case's file for an earlier case's input:
// inode numbers are reused once a file is deleted.
void protect_inputs(bool on = true);

// Records `path` as read by this process (nothing when it does not exist, or protection is off),
// under the name `shown` where given: the file's own name when `path` is the /proc/self/fd path it
// was read through, so that a refusal names the file the user knows.
void note_input(const std::filesystem::path& path, const std::filesystem::path& shown = {});

// The noted input that `output` is, if any.
std::optional<std::filesystem::path> noted_input_at(const std::filesystem::path& output);

// Fails, naming `option` and both paths, when `output` is one of `inputs` or a noted input: a usage
// error (exit 2), since the command line named the output and, directly or through a folder or
// manifest it named, the input.
Result<void> check_not_an_input(const std::filesystem::path& output, std::string_view option,
                                std::span<const std::filesystem::path> inputs = {});

// Fails, naming `option`, when two of `paths` are the same file however they are spelled
// (`a.exr ./a.exr`, a link, a hard link): an input given twice would only weigh twice.
Result<void> check_distinct_files(std::span<const std::string> paths, std::string_view option);

} // namespace kdop
