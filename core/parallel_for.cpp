#include "core/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace kdop {

unsigned core_count() { return std::max(1u, std::thread::hardware_concurrency()); }

unsigned worker_count(unsigned requested) { return requested ? requested : core_count(); }

void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& body,
                  const std::function<void()>& on_worker_exit) {
    std::atomic<std::size_t> next{0};
    std::mutex failure_mutex;
    std::exception_ptr failure;
    auto work = [&] {
        for (std::size_t i; (i = next++) < count;) {
            try {
                body(i);
            } catch (...) {
                std::lock_guard lock(failure_mutex);
                if (!failure) failure = std::current_exception();
                next = count; // the others take no new item
            }
        }
        if (on_worker_exit) on_worker_exit();
    };
    {
        // Always on workers, even one: the exit hook must not run on the caller's thread (GLPK's
        // would free the caller's own problems).
        std::vector<std::jthread> pool;
        for (std::size_t t = 0; t < std::min<std::size_t>(worker_count(threads), count); ++t) pool.emplace_back(work);
    } // joined here
    if (failure) std::rethrow_exception(failure);
}

std::jthread start_worker(std::function<void()> body) { return std::jthread(std::move(body)); }

} // namespace kdop
