#include "harness/subprocess.h"

#include "core/interrupt.h"

#include <fmt/format.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <spawn.h>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace kdop {

std::filesystem::path find_program(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "");
    for (std::string dir; std::getline(dirs, dir, ':');) {
        std::filesystem::path candidate = std::filesystem::path(dir) / name;
        if (!dir.empty() && access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    return {};
}

Result<int> run_program(const std::vector<std::string>& argv, const std::filesystem::path& log,
                        const std::vector<std::string>& environment) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    // Added variables replace inherited ones of the same name.
    std::vector<std::string> env_text = environment;
    for (char** e = environ; *e; ++e) {
        const std::string_view entry(*e);
        const std::string_view name = entry.substr(0, entry.find('=') + 1);
        bool replaced = false;
        for (const std::string& added : environment) replaced |= added.starts_with(name);
        if (!replaced) env_text.emplace_back(entry);
    }
    std::vector<char*> env;
    for (std::string& e : env_text) env.push_back(e.data());
    env.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    // The child starts with no signal blocked: kdop blocks the signals its watcher thread waits
    // for (core/interrupt.h), and a child inherits the mask. Handlers need no resetting (exec gives
    // a caught signal its default action), and a signal ignored when kdop started stays ignored
    // in the child, as it would have without kdop (nohup's SIGHUP).
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t none;
    sigemptyset(&none);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
    pid_t pid = 0;
    OnInterrupt stop_child;
    {
        auto held = hold_interrupts(); // the child and its undo step come into being together
        const int spawned = posix_spawn(&pid, args[0], &actions, &attributes, args.data(), env.data());
        posix_spawn_file_actions_destroy(&actions);
        posix_spawnattr_destroy(&attributes);
        if (spawned != 0) return fail(fmt::format("cannot start {}: {}", argv[0], std::strerror(spawned)));
        // An interrupted run ends the child and waits for it (without reaping it: this thread may)
        // before its scratch folder goes.
        stop_child = OnInterrupt([pid] {
            kill(pid, SIGTERM);
            siginfo_t info;
            while (waitid(P_PID, id_t(pid), &info, WEXITED | WNOWAIT) < 0 && errno == EINTR) {
            }
        });
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return fail(fmt::format("waiting for {}: {}", argv[0], std::strerror(errno)));
    stop_child.forget(); // reaped: its pid may be another process's now
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string log_tail(const std::filesystem::path& log, int count) {
    std::ifstream in(log);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    std::string out;
    for (std::size_t i = lines.size() > std::size_t(count) ? lines.size() - count : 0; i < lines.size(); ++i)
        out += "\n  " + lines[i];
    return out;
}

} // namespace kdop
