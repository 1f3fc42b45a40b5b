// core/parallel_for.h: every index runs once whatever the thread count, and Prefetch hands items
// over in order with at most depth + 1 produced ahead of the one in use, however many there are.
// Both run under ThreadSanitizer in CI (kdop_thread_tests).
#include "core/parallel_for.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

namespace kdop {
namespace {

TEST(ParallelFor, EveryIndexRunsOnceOnAnyThreadCount) {
    for (unsigned threads : {1u, 3u, 8u}) {
        std::vector<std::atomic<int>> runs(100);
        parallel_for(runs.size(), threads, [&](std::size_t i) { ++runs[i]; });
        for (const auto& r : runs) EXPECT_EQ(r.load(), 1) << threads << " threads";
    }
    EXPECT_THROW(parallel_for(10, 2,
                              [](std::size_t i) {
                                  if (i == 7) throw std::runtime_error("seven");
                              }),
                 std::runtime_error);
}

// An item that counts how many of its kind are alive: what a frame read ahead holds in memory.
struct Counted {
    explicit Counted(std::size_t i, std::atomic<int>& alive, std::atomic<int>& most) : index(i), alive_(&alive) {
        const int now = ++alive;
        for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);) {
        }
    }
    Counted(Counted&& other) noexcept : index(other.index), alive_(std::exchange(other.alive_, nullptr)) {}
    Counted& operator=(Counted&&) = delete;
    ~Counted() {
        if (alive_) --*alive_;
    }
    std::size_t index;
    std::atomic<int>* alive_;
};

TEST(Prefetch, HandsItemsOverInOrderHoldingAFewAtMost) {
    std::atomic<int> alive{0}, most{0};
    constexpr std::size_t count = 500, depth = 2;
    {
        Prefetch<std::unique_ptr<Counted>> ahead(
            count, depth, [&](std::size_t i) { return std::make_unique<Counted>(i, alive, most); });
        for (std::size_t i = 0; i < count; ++i) {
            const std::unique_ptr<Counted> item = ahead.take();
            ASSERT_EQ(item->index, i);
        }
    }
    EXPECT_EQ(alive.load(), 0);
    // In the queue (depth), being produced (1) and in use (1): bounded however long the sequence.
    EXPECT_LE(most.load(), int(depth) + 2);
    EXPECT_GE(most.load(), 1);
}

TEST(Prefetch, AnItemThatFailsFailsItsTakeAndStopsTheRest) {
    std::atomic<int> produced{0};
    Prefetch<int> ahead(100, 3, [&](std::size_t i) {
        ++produced;
        if (i == 4) throw std::runtime_error("frame 4 is unreadable");
        return int(i);
    });
    for (int i = 0; i < 4; ++i) EXPECT_EQ(ahead.take(), i);
    EXPECT_THROW(ahead.take(), std::runtime_error);
    EXPECT_EQ(produced.load(), 5);
}

TEST(Prefetch, LeavingEarlyStopsTheWorker) {
    std::atomic<int> produced{0};
    {
        Prefetch<int> ahead(1000000, 2, [&](std::size_t i) { return ++produced, int(i); });
        EXPECT_EQ(ahead.take(), 0);
    } // must not read the other 999,999
    EXPECT_LE(produced.load(), 4);
}

} // namespace
} // namespace kdop
