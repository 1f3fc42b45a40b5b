// What SIGINT and SIGTERM do to a kdop program: undo what it left unfinished, then exit 130 or 143.
//
// handle_interrupts() blocks both signals in the calling thread before any other thread starts
// (every thread after it, glslang's, lavapipe's and OpenImageIO's, inherits the mask) and starts
// one watcher thread that waits for them with sigwait(). An ordinary thread, not a signal
// handler, so the undo steps may do anything: remove a folder tree, wait for a child. On a
// signal the watcher prints "<program>: interrupted", takes the lock every registered step is
// changed under, runs the undo steps still registered (newest first) and _exit()s with 128 +
// the signal's number, as a shell reports it.
//
// A crash (SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT: a driver's fault, an abort in a library) runs
// the same undo steps, where it can take their lock, and then ends the process as the signal would.
//
// What registers an undo step: an output set being written (its temporaries, the files it moved
// aside, the folders it made; core/write_files.h), a scratch folder (harness/scratch_directory.h)
// and a child process (harness/subprocess.h). A program that never calls handle_interrupts()
// (the test binary) registers the same steps; they are simply never run.
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>

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

// The interrupt lock: while it is held, no undo step runs, so a step's owner changes the state the
// step undoes (a path added to a list, a set of renames) without the watcher seeing it half done.
// Hold it briefly: an interrupted program waits for it before it can exit.
std::unique_lock<std::recursive_mutex> hold_interrupts();

// For tests of the above in a child process: when the environment variable KDOP_TEST_HOLD names
// `point`, prints "<point>: holding for a signal (KDOP_TEST_HOLD)" to stderr and waits here until
// a signal arrives. Costs one getenv otherwise.
void test_hold_point(const char* point);

} // namespace kdop
