#include "tests/test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace kdop::test {
namespace fs = std::filesystem;

std::string data_path(const std::string& name) { return std::string(KDOP_TEST_DATA_DIR) + "/" + name; }

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::vector<std::map<std::string, std::string>> csv_rows(const std::string& csv) {
    auto cells = [](const std::string& line) {
        std::vector<std::string> out;
        for (std::size_t b = 0, e; b <= line.size(); b = e + 1) {
            e = std::min(line.find(',', b), line.size());
            out.push_back(line.substr(b, e - b));
        }
        return out;
    };
    std::istringstream in(csv);
    std::string line;
    std::getline(in, line);
    const std::vector<std::string> header = cells(line);
    std::vector<std::map<std::string, std::string>> rows;
    while (std::getline(in, line)) {
        const std::vector<std::string> fields = cells(line);
        std::map<std::string, std::string>& row = rows.emplace_back();
        for (std::size_t i = 0; i < header.size() && i < fields.size(); ++i) row[header[i]] = fields[i];
    }
    return rows;
}

void write_file(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

void expect_golden(const std::string& name, const std::string& actual) {
    fs::path golden = fs::path(KDOP_TEST_GOLDEN_DIR) / name;
    const char* update = std::getenv("KDOP_UPDATE_GOLDEN");
    if (update && std::string(update) == "1") {
        write_file(golden, actual);
        return;
    }
    ASSERT_TRUE(fs::exists(golden)) << golden << " is missing; run the test with KDOP_UPDATE_GOLDEN=1 to create it";
    EXPECT_EQ(actual, read_file(golden)) << "differs from " << golden
                                         << " (if the change is intended: KDOP_UPDATE_GOLDEN=1, then review the diff)";
}

TempDir::TempDir() {
    static std::atomic<int> counter{0};
    path_ = fs::temp_directory_path() / ("kdop-test-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
}

CommandResult run(const std::string& command_line) {
    TempDir dir;
    int status = std::system((command_line + " >" + (dir / "out").string() + " 2>" + (dir / "err").string()).c_str());
    int exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return {exit_code, read_file(dir / "out"), read_file(dir / "err")};
}

std::string shell_word(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

CommandResult run(const std::vector<std::string>& arguments, const std::filesystem::path& cwd) {
    std::string line = cwd.empty() ? "" : "cd " + shell_word(cwd.string()) + " &&";
    for (const std::string& a : arguments) line += " " + shell_word(a);
    return run(line);
}

std::string kdop_binary() { return KDOP_CLI_PATH; }
std::string kdop_gen_binary() { return KDOP_GEN_PATH; }

#ifdef KDOP_MPIEXEC
std::string mpirun_np() {
    // Open MPI refuses root unless told; CI runs as root.
    return fmt::format("{} --oversubscribe{} -np ", KDOP_MPIEXEC, geteuid() == 0 ? " --allow-run-as-root" : "");
}
#endif

} // namespace kdop::test
