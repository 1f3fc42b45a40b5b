// What a signal that would end a kdop program does: undo what the run left unfinished, then exit
// 128 + the signal's number, as a shell reports it (SIGHUP 129, SIGINT 130, SIGPIPE 141, SIGTERM 143).
//
// The signals: every one whose default action ends the process (signal(7)) but the crash signals
// below and the realtime ones (a library may use one; nothing sends them to kdop): SIGHUP, SIGINT,
// SIGQUIT, SIGTERM, SIGALRM, SIGUSR1, SIGUSR2, SIGPIPE, SIGXCPU, SIGXFSZ, SIGVTALRM, SIGPROF,
// SIGIO, SIGPWR and SIGSTKFLT. Only those whose action is still the default when the program
// starts are taken: one ignored then stays ignored, in kdop and in its children (nohup ignores
// SIGHUP, a shell ignores SIGINT and SIGQUIT for a job it starts in the background, and a program
// started so must not die of them), and one a library caught before main keeps its handler.
// SIGQUIT, SIGXCPU and SIGXFSZ end the run as the others do, without their default's core dump.
//
// handle_interrupts() blocks them in the calling thread before any other thread starts (every
// thread after it, glslang's, lavapipe's and OpenImageIO's, inherits the mask) and starts one
// watcher thread that waits for them with sigwait(). An ordinary thread, not a signal handler, so
// the undo steps may do anything: remove a folder tree, wait for a child. On a signal the watcher
// writes "<program>: interrupted (<signal>)" to stderr, takes the lock every registered step is
// changed under, runs the undo steps still registered (newest first) and _exit()s with 128 + the
// signal's number.
//
// SIGPIPE and SIGXFSZ come from a write() (to a pipe no one reads, as in `kdop ... 2>&1 | head`;
// past `ulimit -f`) and go to the thread that wrote; blocked, they would stay pending on that
// thread, unseen by the watcher, and write() would just fail. So only the watcher blocks them; in
// every other thread a handler sends the same signal on to the watcher (pthread_kill: the number
// and the exit status stay the signal's own, and no realtime signal is taken from the libraries)
// and then stops the thread that wrote where it is, as the default action would have stopped the
// process, until the watcher ends it. A thread that holds the interrupt lock goes on instead, its
// write failed, so that the watcher can take the lock. A stopped thread may hold a lock of its
// own, stdio's for the stream it wrote to: the watcher and the undo steps take none of those (the
// watcher writes its line with write(2)).
//
// A crash (SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGSYS, SIGTRAP: a driver's fault, an abort in
// a library) runs the same undo steps, where it can take their lock, and then ends the process as
// the signal would; if a step is stuck in what the crash broke, an alarm five seconds later ends it
// the same way, whether the alarm comes to the crashed thread or to the watcher.
//
// What registers an undo step: an output set being written (its temporaries, the files it moved
// aside, the folders it made; core/write_files.h), a scratch folder (harness/scratch_directory.h)
// and a child process (harness/subprocess.h; a child starts with no signal blocked and, exec
// resetting handlers, the default action for the signals kdop takes). A program that never calls
// handle_interrupts() (the test binary) registers the same steps; they are simply never run.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <pthread.h>

namespace kdop {

// Once, first thing in main(); `program` prefixes the message.
void handle_interrupts(const char* program);

// Whether a signal has arrived (its undo steps may be running or about to run).
bool interrupted();

// An undo step, registered until the guard dies (or forget() is called). It runs on the watcher
// thread with the interrupt lock held, so it sees whatever state its owner last changed under
// hold_interrupts().
class OnInterrupt {
public:
    OnInterrupt() = default;
    explicit OnInterrupt(std::function<void()> undo);
    ~OnInterrupt() { forget(); }
    OnInterrupt(OnInterrupt&& other) noexcept : id_(other.id_) { other.id_ = 0; }
    OnInterrupt& operator=(OnInterrupt&& other) noexcept;
    OnInterrupt(const OnInterrupt&) = delete;
    OnInterrupt& operator=(const OnInterrupt&) = delete;
    void forget();

private:
    std::uint64_t id_ = 0;
};

// The interrupt lock, recursive. It knows its holder, so that the SIGPIPE and SIGXFSZ handler
// never stops the thread that holds it (the watcher would wait for it for ever).
class InterruptLock {
public:
    void lock();
    bool try_lock();
    void unlock();
    bool held_here() const; // async-signal-safe

private:
    std::recursive_mutex mutex_;
    std::atomic<pthread_t> holder_{};
    int depth_ = 0; // changed by the holder only
};

// The interrupt lock: while it is held, no undo step runs, so a step's owner changes the state the
// step undoes (a path added to a list, a set of renames) without the watcher seeing it half done.
// Hold it briefly: an interrupted program waits for it before it can exit.
std::unique_lock<InterruptLock> hold_interrupts();

// For tests of the above in a child process: when the environment variable KDOP_TEST_HOLD names
// `point`, prints "<point>: holding for a signal (KDOP_TEST_HOLD)" to stderr and waits here until
// a signal arrives. Costs one getenv otherwise.
void test_hold_point(const char* point);
// The same, but once the signal has arrived the caller goes on: for a point inside a step that holds
// the interrupt lock (the moves of an output set), which the signal's undo steps wait for.
void test_pause_point(const char* point);

} // namespace kdop
