// The one place kdop starts worker threads (the interrupt watcher aside) and reads the core count.
// Variant builds, callgrind runs, the CPU reference, the ideal clip and the axis fit all share work
// this way: each worker takes the next index until none is left, so the order items finish in
// varies, and callers write each item's result to its own slot to stay deterministic. A sequence's
// frames are read ahead on one worker (Prefetch), handed over in order.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace kdop {

// The machine's cores as the standard library reports them, at least 1.
unsigned core_count();

// `requested` workers, or core_count() when it is 0.
unsigned worker_count(unsigned requested);

// Runs body(i) for every i in [0, count) on worker_count(threads) threads (never more than
// `count`), and returns when every item is done. `on_worker_exit`, when given, runs on each worker
// after its last item: GLPK, for one, keeps per-thread memory until glp_free_env. The first
// exception an item throws stops the others taking new items and is rethrown here.
void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& body,
                  const std::function<void()>& on_worker_exit = {});

// A worker thread running `body` (joined when the returned thread is destroyed): Prefetch's.
std::jthread start_worker(std::function<void()> body);

// Produces items 0, 1, ... count - 1 in order on one worker, at most `depth` ahead of the
// consumer: reading a frame from disk overlaps the work on the last one, and memory holds at most
// depth + 1 items besides the one being worked on, however many there are. An exception `produce`
// throws comes out of the take() of its item. Destroying it stops the worker after its current item.
template <class T>
class Prefetch {
public:
    Prefetch(std::size_t count, std::size_t depth, std::function<T(std::size_t)> produce)
        : count_(count), depth_(depth > 0 ? depth : 1), produce_(std::move(produce)),
          worker_(start_worker([this] { run(); })) {}
    ~Prefetch() {
        {
            std::lock_guard lock(mutex_);
            stop_ = true;
        }
        changed_.notify_all();
    } // worker_ is joined here, first of the members
    Prefetch(const Prefetch&) = delete;
    Prefetch& operator=(const Prefetch&) = delete;

    // The next item, waiting until it is produced. At most `count` calls.
    T take() {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [this] { return !ready_.empty() || failure_; });
        if (ready_.empty()) std::rethrow_exception(failure_);
        T item = std::move(ready_.front());
        ready_.pop_front();
        changed_.notify_all();
        return item;
    }

private:
    void run() {
        for (std::size_t i = 0; i < count_; ++i) {
            {
                std::unique_lock lock(mutex_);
                changed_.wait(lock, [this] { return stop_ || ready_.size() < depth_; });
                if (stop_) return;
            }
            try {
                T item = produce_(i);
                std::lock_guard lock(mutex_);
                ready_.push_back(std::move(item));
            } catch (...) {
                std::lock_guard lock(mutex_);
                failure_ = std::current_exception();
            }
            changed_.notify_all();
            if (failure_) return;
        }
    }

    const std::size_t count_, depth_;
    std::function<T(std::size_t)> produce_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<T> ready_;
    std::exception_ptr failure_;
    bool stop_ = false;
    std::jthread worker_; // last: started once the rest is ready, joined before the rest goes
};

} // namespace kdop
