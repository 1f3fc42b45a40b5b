// Every signal that would end kdop ends it as SIGTERM does (core/interrupt.h): what the run left
// unfinished goes (its scratch folder in TMPDIR, the temporaries in --out), the previous outputs
// stay as they were, and it exits 128 + the signal's number, as a shell reports it. A signal
// ignored when kdop started (nohup's SIGHUP) stays ignored.
#include "core/interrupt.h"
#include "harness/subprocess.h"

#include "tests/interrupt_support.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <map>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace kdop {
namespace {
namespace fs = std::filesystem;

// A `kdop accuracy` run of a second that makes a scratch folder in TMPDIR before its first progress
// line and keeps it while it writes its outputs: held before its moves (write_atomically), both
// that folder and its set's temporaries are there, beside the outputs of a previous run.
struct AccuracyRun {
    test::TempDir dir;
    fs::path out = dir / "accuracy", tmp = dir / "tmp";
    std::map<std::string, std::string> previous;

    AccuracyRun() {
        fs::create_directory(tmp);
        auto first = test::run(environment() + " " + command());
        EXPECT_EQ(first.exit_code, 0) << first.err;
        previous = test::snapshot(out);
        EXPECT_FALSE(previous.empty());
    }
    std::string command() const {
        return test::kdop_binary() +
               " accuracy --size 16 --sets aabb --modes clip --neighborhoods n9 --volume-samples 0 --no-charts --out " +
               out.string();
    }
    std::string environment() const { return "TMPDIR=" + tmp.string(); }
    // The files of --out added, removed or changed since the previous run, by name.
    std::vector<std::string> changed_files() const {
        std::vector<std::string> names;
        const auto now = test::snapshot(out);
        for (const auto& [name, bytes] : now)
            if (!previous.contains(name) || previous.at(name) != bytes) names.push_back(name);
        for (const auto& [name, bytes] : previous)
            if (!now.contains(name)) names.push_back(name);
        return names;
    }
    bool has_scratch_and_temporaries() const { return !fs::is_empty(tmp) && test::has_temporaries(out); }

    // Nothing of an ended run is left; then the folders are as before it, whatever it left, so that
    // the next case starts from the same state.
    void expect_nothing_left(const std::string& what) {
        EXPECT_TRUE(fs::is_empty(tmp)) << what << ": its kdop-accuracy-* is left";
        EXPECT_FALSE(test::has_temporaries(out)) << what << ": *.kdop-partial-* are left";
        EXPECT_EQ(changed_files(), std::vector<std::string>{}) << what << ": the previous outputs changed";
        fs::remove_all(tmp);
        fs::create_directory(tmp);
        for (const auto& entry : fs::directory_iterator(out))
            if (!previous.contains(entry.path().filename().string())) fs::remove_all(entry.path());
    }
};

std::string name_of(int signal) { return std::string("SIG") + sigabbrev_np(signal); }

// How a run ended, for a message: the signal that killed it, and its last lines (after the
// progress lines, the hold and the watcher's).
std::string told(const test::Ending& ended) {
    const std::size_t from = ended.err.size() > 300 ? ended.err.size() - 300 : 0;
    return (ended.signal ? name_of(ended.signal) + " killed it; " : "") + "it wrote: ..." + ended.err.substr(from);
}

TEST(CliSignals, EverySignalThatEndsARunRemovesWhatItLeftUnfinished) {
    AccuracyRun run;
    // signal(7)'s signals whose default action ends the process, the crash signals aside
    // (CliInterrupt.ACrashLeavesNoScratchFolderNorTemporary). SIGPIPE and SIGXFSZ are sent to the
    // process here, as kill does; raised by a write, below.
    const int signals[] = {SIGHUP,  SIGINT,  SIGQUIT, SIGTERM,   SIGALRM, SIGUSR1, SIGUSR2,  SIGPIPE,
                           SIGXCPU, SIGXFSZ, SIGIO,   SIGVTALRM, SIGPROF, SIGPWR,  SIGSTKFLT};
    for (int signal : signals) {
        bool held_with_leftovers = false;
        auto ended = test::interrupt_at(run.command(), {signal}, run.environment(), "write_atomically",
                                        [&] { held_with_leftovers = run.has_scratch_and_temporaries(); });
        EXPECT_TRUE(held_with_leftovers) << name_of(signal) << " came when there was nothing to remove";
        EXPECT_EQ(ended.exit_code, 128 + signal) << name_of(signal) << ": " << told(ended);
        EXPECT_NE(ended.err.find(std::string("kdop: interrupted (") + strsignal(signal) + ")"), std::string::npos)
            << told(ended);
        run.expect_nothing_left(name_of(signal));
    }
}

// `kdop accuracy ... 2>&1 | head` once head has gone: kdop's first progress line, written after its
// scratch folder is made, meets a pipe no one reads, and SIGPIPE comes to the thread that wrote.
TEST(CliSignals, APipeNoOneReadsEndsTheRunWith141AndNothingLeft) {
    AccuracyRun run;
    auto ended = test::run_until_it_ends(run.command(), run.environment(), [] {
        int ends[2];
        if (pipe(ends) != 0) _exit(126);
        close(ends[0]); // before kdop starts: its first write fails, whenever it comes
        dup2(ends[1], 1);
        dup2(ends[1], 2);
    });
    EXPECT_EQ(ended.exit_code, 141) << told(ended);
    run.expect_nothing_left("a closed pipe");
}

// A file grown past `ulimit -f`: SIGXFSZ comes to the thread that wrote, here the one writing the
// set's temporaries (accuracy.json, about 30 kB, over the limit; stderr's lines stay under it).
TEST(CliSignals, AFileOverTheSizeLimitEndsTheRunWith153AndNothingLeft) {
    AccuracyRun run;
    auto ended = test::run_until_it_ends(run.command(), run.environment(), [] {
        const rlimit limit{20000, 20000};
        setrlimit(RLIMIT_FSIZE, &limit);
    });
    EXPECT_EQ(ended.exit_code, 153) << told(ended);
    EXPECT_NE(ended.err.find("kdop: interrupted (File size limit exceeded)"), std::string::npos) << told(ended);
    run.expect_nothing_left("the file size limit");
}

// nohup leaves SIGHUP ignored, and a program it starts must not die of a hang-up. The SIGHUP is
// sent first: had kdop taken it, it would have ended the run (of two pending signals the lower
// number is taken first); ignored, it is discarded, and the SIGTERM after it ends the run.
// A signal amid the moves of an output set (finding 8: SIGHUP there left a new taa.csv beside the
// old run's frames) waits for them: the folder then holds the new set whole, its listing's files and
// no file of the run before (here the charts, which the new run leaves out), and no temporary.
TEST(CliSignals, ASignalAmidTheMovesLeavesTheNewSetWhole) {
    test::TempDir dir;
    const fs::path out = dir / "accuracy";
    const std::string command = test::kdop_binary() +
                                " accuracy --size 16 --sets aabb --modes clip --neighborhoods n9 --volume-samples 0 "
                                "--out " +
                                out.string();
    auto first = test::run(command);
    ASSERT_EQ(first.exit_code, 0) << first.err;
    ASSERT_TRUE(fs::exists(out / "pareto-grass.png")) << "the first run draws its charts (gnuplot)";
    auto ended = test::interrupt_at(command + " --no-charts", {SIGHUP}, "", "commit");
    EXPECT_EQ(ended.exit_code, 128 + SIGHUP) << told(ended);
    EXPECT_FALSE(test::has_temporaries(out));
    std::string listed;
    for (const auto& [name, bytes] : test::snapshot(out))
        if (name != ".kdop-outputs") listed += name + "\n";
    const std::string listing = test::read_file(out / ".kdop-outputs");
    EXPECT_EQ(listing.substr(listing.find('\n') + 1), listed);
    EXPECT_FALSE(fs::exists(out / "pareto-grass.png")) << "the earlier run's chart is left";
}

TEST(CliSignals, ASignalIgnoredWhenKdopStartsStaysIgnored) {
    AccuracyRun run;
    auto ended = test::interrupt_at("nohup " + run.command(), {SIGHUP, SIGTERM}, run.environment());
    EXPECT_EQ(ended.exit_code, 143) << told(ended);
    run.expect_nothing_left("SIGHUP under nohup, then SIGTERM");
}

// A crash whose undo step is stuck (on a lock or in an allocator the crash broke) still ends, by
// the crash's own signal, through the alarm its handler sets, though the watcher thread waits for
// SIGALRM too. The stuck step spins, so that a limit on CPU time (SIGKILL) ends it if not.
TEST(Interrupts, ACrashWhoseUndoStepIsStuckStillEnds) {
    const pid_t pid = fork();
    if (pid == 0) {
        const rlimit cpu{30, 30}, no_core{0, 0};
        setrlimit(RLIMIT_CPU, &cpu);
        setrlimit(RLIMIT_CORE, &no_core);
        handle_interrupts("stuck");
        static const OnInterrupt stuck([] {
            for (volatile bool forever = true; forever;) {
            }
        });
        raise(SIGSEGV);
        _exit(0);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "exited " << WEXITSTATUS(status);
    EXPECT_EQ(WTERMSIG(status), SIGSEGV) << name_of(WTERMSIG(status)) << " ended it";
}

// SIGPIPE in a thread that holds the interrupt lock does not stop that thread, which would keep the
// watcher from the lock for ever: its write fails, it goes on and lets the lock go, and the
// watcher ends the process with 141. A spinning thread gives a limit on CPU time something to
// count, so that a deadlock ends (SIGKILL) rather than hangs the test.
TEST(Interrupts, SigpipeUnderTheInterruptLockLetsTheLockGo) {
    const pid_t pid = fork();
    if (pid == 0) {
        const rlimit cpu{30, 30};
        setrlimit(RLIMIT_CPU, &cpu);
        handle_interrupts("held");
        std::thread([] {
            for (volatile bool forever = true; forever;) {
            }
        }).detach();
        int ends[2];
        if (pipe(ends) != 0) _exit(126);
        close(ends[0]);
        {
            auto held = hold_interrupts();
            if (write(ends[1], "x", 1) >= 0 || errno != EPIPE) _exit(1);
        }
        for (;;) pause(); // for the watcher, which waited for the lock
    }
    int status = 0;
    waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 141)
        << (WIFSIGNALED(status) ? name_of(WTERMSIG(status)) + " ended it"
                                : "exited " + std::to_string(WEXITSTATUS(status)));
}

// A child kdop starts (gnuplot, valgrind) has no signal blocked and none caught, whatever kdop
// blocks and catches for its watcher: it ends on a signal as it would without kdop.
TEST(Interrupts, AChildStartsWithNoSignalBlockedNorCaught) {
    test::TempDir dir;
    const fs::path log = dir / "status";
    const pid_t pid = fork();
    if (pid == 0) {
        handle_interrupts("child");
        auto ran = run_program({"/bin/cat", "/proc/self/status"}, log);
        _exit(ran && *ran == 0 ? 0 : 1);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    const std::string child = test::read_file(log);
    EXPECT_NE(child.find("SigBlk:\t0000000000000000\n"), std::string::npos) << child;
    EXPECT_NE(child.find("SigCgt:\t0000000000000000\n"), std::string::npos) << child;
}

} // namespace
} // namespace kdop
