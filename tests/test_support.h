// Helpers shared by the tests: test data and golden files, temporary directories, and running
// the kdop binaries as a user would.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace kdop::test {

std::string data_path(const std::string& name); // tests/data/<name>

// Compares `actual` with tests/golden/<name>; with KDOP_UPDATE_GOLDEN=1 in the environment,
// rewrites the golden file instead (then review the diff).
void expect_golden(const std::string& name, const std::string& actual);

std::string read_file(const std::filesystem::path& path);
void write_file(const std::filesystem::path& path, const std::string& text);

// A fresh, empty directory under the system temp directory, removed when this object dies.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    std::filesystem::path path_;
};

struct CommandResult {
    int exit_code;
    std::string out, err;
};

// Runs a shell command line, capturing stdout and stderr.
CommandResult run(const std::string& command_line);

// `text` as one word of a shell command line, whatever it holds (quotes, $(), backticks, line
// breaks): single-quoted, each ' written as '\''.
std::string shell_word(const std::string& text);
// Runs `arguments` as one command, each its own word, in `cwd` where given.
CommandResult run(const std::vector<std::string>& arguments, const std::filesystem::path& cwd = {});

// The rows of a CSV kdop wrote (harness/table.h: a header line, then one line per row; no field of
// the tables tests read is quoted), each as its header's names to its fields.
std::vector<std::map<std::string, std::string>> csv_rows(const std::string& csv);

// Absolute paths of the built binaries.
std::string kdop_binary();
std::string kdop_gen_binary();

#ifdef KDOP_MPIEXEC
// `mpirun ... -np `, to be followed by a rank count: the mpirun kdop was built against, allowed
// more ranks than cores and, as CI runs, root.
std::string mpirun_np();
#endif

} // namespace kdop::test
