#include "tests/interrupt_support.h"

#include "tests/test_support.h"

#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace kdop::test {
namespace fs = std::filesystem;

namespace {

// sh -c "<environment> exec <command>", stderr to `err` and stdout to /dev/null, after `prepare`:
// `exec`, so that the signals reach kdop and not the shell. kdop starts with every signal at its
// default action and none blocked, as from a terminal's shell, whatever the tests were started
// with (under nohup, a signal kdop finds ignored stays ignored and would never end it).
pid_t start(const std::string& line, const fs::path& err, const std::function<void()>& prepare) {
    const pid_t pid = fork();
    if (pid == 0) {
        for (int signal = 1; signal < NSIG; ++signal) std::signal(signal, SIG_DFL); // KILL, STOP: refused
        sigset_t none;
        sigemptyset(&none);
        sigprocmask(SIG_SETMASK, &none, nullptr);
        const int fd = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(fd, 2);
        const int null = open("/dev/null", O_WRONLY);
        dup2(null, 1);
        if (prepare) prepare();
        execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    return pid;
}

Ending ending(pid_t pid, const fs::path& err, const std::string& before = "") {
    int status = 0;
    waitpid(pid, &status, 0);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, WIFSIGNALED(status) ? WTERMSIG(status) : 0,
            before + read_file(err)};
}

} // namespace

Ending interrupt_at(const std::string& command, const std::vector<int>& signals, const std::string& environment,
                    const std::string& point, const std::function<void()>& when_held) {
    TempDir dir;
    const fs::path err = dir / "err";
    const pid_t pid = start("KDOP_TEST_HOLD=" + point + " " + environment + " exec " + command, err, {});
    bool holding = false;
    for (int i = 0; i < 12000 && !holding; ++i) { // up to two minutes
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        holding = read_file(err).find("holding for a signal") != std::string::npos;
        int status = 0;
        if (!holding && waitpid(pid, &status, WNOHANG) == pid)
            return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, WIFSIGNALED(status) ? WTERMSIG(status) : 0,
                    "ended before its hold point: " + read_file(err)};
    }
    if (!holding) {
        kill(pid, SIGKILL);
        return ending(pid, err, "never held at " + point + ": ");
    }
    if (when_held) when_held();
    for (int signal : signals) kill(pid, signal);
    return ending(pid, err);
}

Ending run_until_it_ends(const std::string& command, const std::string& environment,
                         const std::function<void()>& prepare) {
    TempDir dir;
    const fs::path err = dir / "err";
    return ending(start(environment + " exec " + command, err, prepare), err);
}

std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> files;
    if (!fs::exists(dir)) return files;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        files[fs::relative(entry.path(), dir).string()] = entry.is_regular_file() ? read_file(entry.path()) : "/";
    return files;
}

bool has_temporaries(const fs::path& dir) {
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.path().filename().string().find("kdop-partial") != std::string::npos) return true;
    return false;
}

} // namespace kdop::test
