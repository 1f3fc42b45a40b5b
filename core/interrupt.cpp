#include "interrupt.h"

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

} // namespace

void handle_interrupts(const char* program) {
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
        for (auto it = r.undo.rbegin(); it != r.undo.rend(); ++it) {
            try {
                it->second();
            } catch (...) {
                // An undo step that fails leaves its part; the others still run.
            }
        }
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
