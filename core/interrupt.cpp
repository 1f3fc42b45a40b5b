#include "core/interrupt.h"

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <pthread.h>
#include <thread>
#include <unistd.h>

namespace kdop {

namespace {

struct Registry {
    std::recursive_mutex lock;
    std::map<std::uint64_t, std::function<void()>> undo; // by registration order
    std::uint64_t next_id = 1;
};

// Never destroyed: the watcher may use it while static destructors run at exit.
Registry& registry() {
    static Registry* r = new Registry;
    return *r;
}

std::atomic<bool> signalled{false};

sigset_t interrupt_signals() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    return set;
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

// A crash (a driver's segmentation fault, an abort inside a library) ends the process without its
// destructors: the undo steps run here first, so no temporary or scratch folder outlives it, as
// LLVM's tools remove their output files on a crash signal. Not async-signal-safe, since the steps
// remove folders, so it is guarded: the steps run only if their lock can be taken, and an alarm
// ends a step that deadlocks inside the allocator the crash may have broken. Then the signal is
// raised again with its default action, for the exit status and the core dump.
void undo_on_crash(int signal) {
    alarm(5);
    Registry& r = registry();
    if (r.lock.try_lock()) run_undo_steps(r);
    std::signal(signal, SIG_DFL);
    std::raise(signal);
}

} // namespace

void handle_interrupts(const char* program) {
    for (int crash : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT}) {
        struct sigaction action {};
        action.sa_handler = undo_on_crash;
        sigemptyset(&action.sa_mask);
        action.sa_flags = SA_RESETHAND | SA_NODEFER;
        sigaction(crash, &action, nullptr);
    }
    const sigset_t set = interrupt_signals();
    if (pthread_sigmask(SIG_BLOCK, &set, nullptr) != 0) return; // cannot happen with valid signals
    std::thread([set, program] {
        int signal = 0;
        while (sigwait(&set, &signal) != 0) {
        }
        signalled = true;
        std::fprintf(stderr, "\n%s: interrupted (%s); removing unfinished output\n", program, strsignal(signal));
        Registry& r = registry();
        r.lock.lock(); // kept: nothing may change the undone state after this
        run_undo_steps(r);
        std::_Exit(128 + signal);
    }).detach();
}

bool interrupted() { return signalled; }

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

std::unique_lock<std::recursive_mutex> hold_interrupts() { return std::unique_lock(registry().lock); }

void test_hold_point(const char* point) {
    const char* wanted = std::getenv("KDOP_TEST_HOLD");
    if (!wanted || std::strcmp(wanted, point) != 0) return;
    std::fprintf(stderr, "%s: holding for a signal (KDOP_TEST_HOLD)\n", point);
    std::fflush(stderr);
    while (!interrupted()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    // The watcher exits the process; this thread only waits for it.
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
}

} // namespace kdop
