// The one place kdop starts worker threads (the interrupt watcher aside) and reads the core count.
// Variant builds, callgrind runs, the CPU reference, the ideal clip and the axis fit all share work
// this way: each worker takes the next index until none is left, so the order items finish in
// varies, and callers write each item's result to its own slot to stay deterministic.
#pragma once

#include <cstddef>
#include <functional>

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

} // namespace kdop
