#include "core/interrupt.h"

#include <fmt/format.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <thread>
#include <unistd.h>

namespace kdop {

namespace {

struct Registry {
    InterruptLock lock;
    std::map<std::uint64_t, std::function<void()>> undo; // by registration order
    std::uint64_t next_id = 1;
};

// Never destroyed: the watcher may use it while static destructors run at exit.
Registry& registry() {
    static Registry* r = new Registry;
    return *r;
}

std::atomic<bool> signalled{false};
std::atomic<pthread_t> watcher{};
std::atomic<bool> watcher_started{false};
std::atomic<int> crashing{0}; // the crash signal whose undo steps are running, or 0

// The signals whose default action ends the process (signal(7)), by how they reach the watcher:
// sent to the process, they wait blocked for it; raised by a write() in the thread that wrote,
// they are forwarded to it; a crash runs the undo steps where it happens. The realtime signals
// are left alone: a library may use one, and nothing sends them to kdop.
constexpr int kWaitedFor[] = {SIGHUP,  SIGINT,    SIGQUIT, SIGTERM, SIGALRM, SIGUSR1,  SIGUSR2,
                              SIGXCPU, SIGVTALRM, SIGPROF, SIGIO,   SIGPWR,  SIGSTKFLT};
constexpr int kForwarded[] = {SIGPIPE, SIGXFSZ};
constexpr int kCrashes[] = {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGSYS, SIGTRAP};

// Whether `signal` still has its default action: one ignored by the parent (nohup's SIGHUP, a
// background job's SIGINT) stays ignored, one caught before main keeps its handler.
bool at_default(int signal) {
    struct sigaction current {};
    return sigaction(signal, nullptr, &current) == 0 && !(current.sa_flags & SA_SIGINFO) &&
           current.sa_handler == SIG_DFL;
}

void set_action(int signal, void (*handler)(int), int flags) {
    struct sigaction action {};
    action.sa_handler = handler;
    sigemptyset(&action.sa_mask);
    action.sa_flags = flags;
    sigaction(signal, &action, nullptr);
}

// Runs every registered undo step, newest first; a step that throws leaves its part.
void run_undo_steps(Registry& r) {
    for (auto it = r.undo.rbegin(); it != r.undo.rend(); ++it) {
        try {
            it->second();
        } catch (...) {
        }
    }
}

// Ends the process with the crash signal whose undo steps are stuck, from any thread: its
// default action (a core dump) ends every thread.
[[noreturn]] void end_stuck_crash(int) {
    const int crash = crashing;
    set_action(crash, SIG_DFL, 0);
    sigset_t only;
    sigemptyset(&only);
    sigaddset(&only, crash);
    pthread_sigmask(SIG_UNBLOCK, &only, nullptr);
    raise(crash);
    _exit(128 + crash);
}

// A crash (a driver's segmentation fault, an abort inside a library) ends the process without its
// destructors: the undo steps run here first, so no temporary or scratch folder outlives it, as
// LLVM's tools remove their output files on a crash signal. Not async-signal-safe, since the steps
// remove folders, so it is guarded: the steps run only if their lock can be taken, and an alarm
// ends a step that deadlocks inside the allocator the crash may have broken. The watcher waits
// for SIGALRM too, so the alarm is caught in this thread (unblocked here) or in the watcher, and
// either ends the process as the crash would. Then the signal is raised again with its default
// action, for the exit status and the core dump.
void undo_on_crash(int signal) {
    int none = 0;
    crashing.compare_exchange_strong(none, signal);
    set_action(SIGALRM, end_stuck_crash, 0);
    sigset_t alarm_signal;
    sigemptyset(&alarm_signal);
    sigaddset(&alarm_signal, SIGALRM);
    pthread_sigmask(SIG_UNBLOCK, &alarm_signal, nullptr);
    alarm(5);
    Registry& r = registry();
    if (r.lock.try_lock()) run_undo_steps(r);
    set_action(signal, SIG_DFL, 0);
    raise(signal);
}

// SIGPIPE and SIGXFSZ, raised in the thread whose write() failed: the watcher gets the same
// signal, and this thread stops here, as the default action would stop it with the process. Not
// the holder of the interrupt lock, which the watcher waits for: its write fails and it goes on.
void forward_to_watcher(int signal) {
    const int saved_errno = errno;
    signalled = true;
    pthread_kill(watcher.load(), signal);
    if (!registry().lock.held_here())
        for (;;) pause();
    errno = saved_errno;
}

// The watcher thread: waits for a signal of `waited`, then undoes and exits.
[[noreturn]] void watch(const sigset_t& waited, const char* program) {
    int signal = 0;
    while (sigwait(&waited, &signal) != 0) {
    }
    if (signal == SIGALRM && crashing) end_stuck_crash(SIGALRM); // the crash's alarm: a step is stuck
    signalled = true;
    // write(2), not stdio: a thread SIGPIPE stopped may hold stderr's lock.
    const std::string line =
        fmt::format("\n{}: interrupted ({}); removing unfinished output\n", program, strsignal(signal));
    [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, line.data(), line.size());
    Registry& r = registry();
    r.lock.lock(); // kept: nothing may change the undone state after this
    run_undo_steps(r);
    std::_Exit(128 + signal);
}

} // namespace

void handle_interrupts(const char* program) {
    registry(); // made before any handler may need it
    for (int crash : kCrashes) set_action(crash, undo_on_crash, SA_RESETHAND | SA_NODEFER);
    sigset_t waited, forwarded;
    sigemptyset(&waited);
    sigemptyset(&forwarded);
    for (int signal : kWaitedFor)
        if (at_default(signal)) sigaddset(&waited, signal);
    for (int signal : kForwarded)
        if (at_default(signal)) {
            sigaddset(&waited, signal);
            sigaddset(&forwarded, signal);
        }
    // The watcher starts with all of them blocked; every other thread, this one's mask, with the
    // forwarded ones unblocked again once their handler knows the watcher.
    if (pthread_sigmask(SIG_BLOCK, &waited, nullptr) != 0) return; // cannot happen with valid signals
    std::thread([waited, program] {
        watcher = pthread_self();
        watcher_started = true;
        watcher_started.notify_one();
        watch(waited, program);
    }).detach();
    watcher_started.wait(false);
    for (int signal : kForwarded)
        if (sigismember(&forwarded, signal)) set_action(signal, forward_to_watcher, SA_RESTART);
    pthread_sigmask(SIG_UNBLOCK, &forwarded, nullptr);
}

bool interrupted() { return signalled; }

void InterruptLock::lock() {
    mutex_.lock();
    if (depth_++ == 0) holder_ = pthread_self();
}

bool InterruptLock::try_lock() {
    if (!mutex_.try_lock()) return false;
    if (depth_++ == 0) holder_ = pthread_self();
    return true;
}

void InterruptLock::unlock() {
    if (--depth_ == 0) holder_ = pthread_t{};
    mutex_.unlock();
}

bool InterruptLock::held_here() const { return pthread_equal(holder_.load(), pthread_self()); }

OnInterrupt::OnInterrupt(std::function<void()> undo) {
    auto held = hold_interrupts();
    Registry& r = registry();
    id_ = r.next_id++;
    r.undo.emplace(id_, std::move(undo));
}

OnInterrupt& OnInterrupt::operator=(OnInterrupt&& other) noexcept {
    if (this != &other) {
        forget();
        id_ = other.id_;
        other.id_ = 0;
    }
    return *this;
}

void OnInterrupt::forget() {
    if (!id_) return;
    auto held = hold_interrupts();
    registry().undo.erase(id_);
    id_ = 0;
}

std::unique_lock<InterruptLock> hold_interrupts() { return std::unique_lock(registry().lock); }

namespace {

// Whether KDOP_TEST_HOLD names `point`; then says so and waits until a signal has arrived.
bool wait_at(const char* point) {
    const char* wanted = std::getenv("KDOP_TEST_HOLD");
    if (!wanted || std::strcmp(wanted, point) != 0) return false;
    std::fprintf(stderr, "%s: holding for a signal (KDOP_TEST_HOLD)\n", point);
    std::fflush(stderr);
    while (!interrupted()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return true;
}

} // namespace

void test_hold_point(const char* point) {
    if (!wait_at(point)) return;
    // The watcher exits the process; this thread only waits for it.
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
}

void test_pause_point(const char* point) { wait_at(point); }

} // namespace kdop
