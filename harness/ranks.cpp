#include "harness/ranks.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <iostream>
#include <numeric>
#include <thread>

#include <fcntl.h>
#include <unistd.h>

#ifdef KDOP_WITH_MPI
#include <mpi.h>
#endif

namespace kdop {

bool started_by_launcher() {
    for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
        if (std::getenv(variable)) return true;
    return false;
}

int launched_ranks() {
    for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
        if (const char* size = std::getenv(variable)) return std::max(1, std::atoi(size));
    return 1;
}

Result<Ranks*> Ranks::world() {
    static Ranks ranks;
    static bool started = false;
    if (started || !started_by_launcher()) return &ranks;
    started = true;
#ifdef KDOP_WITH_MPI
    // Only the main thread calls MPI; the worker threads of an evaluation never do.
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    std::atexit([] { MPI_Finalize(); });
    MPI_Comm_rank(MPI_COMM_WORLD, &ranks.rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks.size_);
    return &ranks;
#else
    if (launched_ranks() > 1)
        return fail("this kdop was built without MPI (install libopenmpi-dev and rebuild) and cannot run as "
                    "several ranks; run it without mpirun");
    return &ranks;
#endif
}

namespace {

// Where rank r's share of `count` items starts (r = size: where the last one ends).
std::size_t share_start(std::size_t count, int r, int size) { return count * std::size_t(r) / std::size_t(size); }

} // namespace

std::pair<std::size_t, std::size_t> Ranks::share(std::size_t count) const {
    return {share_start(count, rank_, size_), share_start(count, rank_ + 1, size_)};
}

int Ranks::owner(std::size_t i, std::size_t count) const {
    int r = 0;
    while (r + 1 < size_ && share_start(count, r + 1, size_) <= i) ++r;
    return r;
}

void Ranks::all_gather(std::span<double> all, std::span<const std::size_t> per_item) const {
    if (size_ == 1) return;
#ifdef KDOP_WITH_MPI
    // Each rank's items are contiguous in `all`: one block of doubles per rank, gathered in place.
    std::vector<std::size_t> offset(per_item.size() + 1, 0);
    std::partial_sum(per_item.begin(), per_item.end(), offset.begin() + 1);
    std::vector<int> counts(size_), displacements(size_);
    for (int r = 0; r < size_; ++r) {
        const std::size_t first = share_start(per_item.size(), r, size_),
                          end = share_start(per_item.size(), r + 1, size_);
        displacements[r] = int(offset[first]);
        counts[r] = int(offset[end] - offset[first]);
    }
    MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, all.data(), counts.data(), displacements.data(), MPI_DOUBLE,
                   MPI_COMM_WORLD);
#endif
}

void Ranks::broadcast(std::span<double> values) const {
    if (size_ == 1) return;
#ifdef KDOP_WITH_MPI
    MPI_Bcast(values.data(), int(values.size()), MPI_DOUBLE, 0, MPI_COMM_WORLD);
#endif
}

std::vector<int> Ranks::balance(std::span<const double> costs) const { return balance_over(costs, size_); }

std::vector<int> balance_over(std::span<const double> costs, int ranks) {
    std::vector<std::size_t> order(costs.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::ranges::stable_sort(order, [&](std::size_t a, std::size_t b) { return costs[a] > costs[b]; });
    std::vector<double> load(std::size_t(std::max(ranks, 1)), 0.0);
    std::vector<int> owners(costs.size(), 0);
    for (const std::size_t item : order) {
        const auto least = std::ranges::min_element(load); // the first of equals
        owners[item] = int(least - load.begin());
        *least += costs[item];
    }
    return owners;
}

std::vector<std::string> Ranks::gather_to_root(const std::string& mine) const {
    if (size_ == 1) return {mine};
#ifdef KDOP_WITH_MPI
    std::vector<std::string> all;
    if (is_root()) all.push_back(mine);
    for (int r = 1; r < size_; ++r) {
        if (is_root())
            all.push_back(receive(r));
        else if (r == rank_)
            send(mine, 0);
    }
    return all;
#else
    return {mine};
#endif
}

#ifdef KDOP_WITH_MPI
namespace {
// MPI counts are ints: a message goes as its length, then in pieces of at most 1 GiB.
constexpr std::size_t kPiece = std::size_t(1) << 30;
constexpr int kBytesTag = 7;
} // namespace
#endif

void Ranks::send([[maybe_unused]] const std::string& bytes, [[maybe_unused]] int to) const {
#ifdef KDOP_WITH_MPI
    unsigned long long length = bytes.size();
    MPI_Send(&length, 1, MPI_UNSIGNED_LONG_LONG, to, kBytesTag, MPI_COMM_WORLD);
    for (std::size_t at = 0; at < bytes.size(); at += kPiece)
        MPI_Send(bytes.data() + at, int(std::min(kPiece, bytes.size() - at)), MPI_CHAR, to, kBytesTag, MPI_COMM_WORLD);
#endif
}

std::string Ranks::receive([[maybe_unused]] int from) const {
    std::string bytes;
#ifdef KDOP_WITH_MPI
    unsigned long long length = 0;
    MPI_Recv(&length, 1, MPI_UNSIGNED_LONG_LONG, from, kBytesTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    bytes.resize(length);
    for (std::size_t at = 0; at < bytes.size(); at += kPiece)
        MPI_Recv(bytes.data() + at, int(std::min(kPiece, bytes.size() - at)), MPI_CHAR, from, kBytesTag, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
#endif
    return bytes;
}

#ifdef KDOP_WITH_MPI
namespace {
// Progress messages: a count of steps, or kFinished / kFailed. The world has one Ranks, so its
// messages in flight are kept here: each value stays put (a deque does not move its elements)
// until its send completes.
constexpr int kProgressTag = 8, kLastWordTag = 10;
constexpr std::uint64_t kFinished = ~std::uint64_t(0), kFailed = kFinished - 1;
// Rank 0's last word to each other rank.
constexpr std::uint64_t kDone = 0, kStop = 1;

struct Sends {
    std::deque<std::uint64_t> values;
    std::vector<MPI_Request> requests;
    void send(std::uint64_t value, int to, int tag) {
        values.push_back(value);
        requests.emplace_back();
        MPI_Isend(&values.back(), 1, MPI_UINT64_T, to, tag, MPI_COMM_WORLD, &requests.back());
    }
    void wait() {
        MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
        requests.clear();
        values.clear();
    }
};

// On the other ranks: the counts and the finish sent; whether rank 0's last word has come, and
// what it said; whether the finish has been sent, so that agree() takes the last word first.
Sends progress_sends;
bool last_word_taken = false, stop_said = false, progress_finished_here = false;

// On rank 0: the last words sent, to whom, and what it has heard.
Sends last_words;
std::vector<char> told;    // by rank: its last word sent
int progress_finished = 0; // the other ranks that have said they finished
bool failure_heard = false;

void tell(int rank, std::uint64_t word) {
    int size = 0;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    told.resize(std::size_t(size), 0);
    if (told[std::size_t(rank)]) return;
    told[std::size_t(rank)] = 1;
    last_words.send(word, rank, kLastWordTag);
}

// Rank 0: "stop" to every rank not yet told.
void stop_every_rank() {
    int size = 0;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    for (int r = 1; r < size; ++r) tell(r, kStop);
}

// The other ranks: rank 0's last word, if it has come (or, with `wait`, once it comes).
void take_last_word(bool wait) {
    if (last_word_taken) return;
    int arrived = 1;
    if (!wait) MPI_Iprobe(0, kLastWordTag, MPI_COMM_WORLD, &arrived, MPI_STATUS_IGNORE);
    if (!arrived) return;
    std::uint64_t word = kDone;
    MPI_Recv(&word, 1, MPI_UINT64_T, 0, kLastWordTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    last_word_taken = true;
    stop_said = word == kStop;
}
} // namespace
#endif

void Ranks::tell_progress([[maybe_unused]] std::size_t steps) const {
#ifdef KDOP_WITH_MPI
    if (size_ > 1 && !is_root() && steps > 0) progress_sends.send(steps, 0, kProgressTag);
#endif
}

void Ranks::finish_progress([[maybe_unused]] bool succeeded) const {
#ifdef KDOP_WITH_MPI
    if (size_ == 1 || is_root()) return;
    progress_sends.send(succeeded ? kFinished : kFailed, 0, kProgressTag);
    progress_sends.wait();
    progress_finished_here = true;
#endif
}

std::size_t Ranks::take_progress() const {
    std::size_t steps = 0;
#ifdef KDOP_WITH_MPI
    if (size_ == 1 || !is_root()) return 0;
    for (;;) {
        int arrived = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, kProgressTag, MPI_COMM_WORLD, &arrived, &status);
        if (!arrived) break;
        std::uint64_t count = 0;
        MPI_Recv(&count, 1, MPI_UINT64_T, status.MPI_SOURCE, kProgressTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (count == kFinished || count == kFailed) {
            ++progress_finished;
            failure_heard = failure_heard || count == kFailed;
            tell(status.MPI_SOURCE, kDone); // it has finished: nothing left to stop
            if (failure_heard) stop_every_rank();
        } else {
            steps += std::size_t(count);
        }
    }
#endif
    return steps;
}

bool Ranks::stop_asked() const {
#ifdef KDOP_WITH_MPI
    if (size_ == 1) return false;
    if (is_root()) return failure_heard;
    take_last_word(false);
    return stop_said;
#else
    return false;
#endif
}

void Ranks::wait_for_progress(const std::function<void(std::size_t steps)>& on_steps,
                              [[maybe_unused]] bool succeeded) const {
#ifdef KDOP_WITH_MPI
    if (size_ == 1 || !is_root()) return;
    if (!succeeded) stop_every_rank();
    // Each rank's finish is its last message, so every count has arrived when all have finished.
    for (;;) {
        if (const std::size_t steps = take_progress(); steps > 0) on_steps(steps);
        if (progress_finished == size_ - 1) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    last_words.wait();
    told.clear();
    progress_finished = 0;
    failure_heard = false;
#else
    (void)on_steps;
#endif
}

Result<void> Ranks::agree(Result<void> mine) const {
    if (size_ == 1) return mine;
#ifdef KDOP_WITH_MPI
    // Rank 0's last word after this rank's progress, taken here rather than as it finished: rank 0
    // says it only between its own frames, and this rank has work of its own meanwhile (its
    // viewer's frames). Rank 0 has said every last word before it comes here.
    if (progress_finished_here) {
        take_last_word(true);
        last_word_taken = stop_said = progress_finished_here = false;
    }
    // The lowest failing rank, then its message, broadcast from it.
    int failed = mine ? size_ : rank_, first = size_;
    MPI_Allreduce(&failed, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (first == size_) return {};
    Error error = mine ? Error{} : mine.error();
    // Its length and whether the command line was at fault (exit 2 on every rank), then its text.
    unsigned long header[2] = {error.message.size(), error.usage ? 1ul : 0ul};
    MPI_Bcast(header, 2, MPI_UNSIGNED_LONG, first, MPI_COMM_WORLD);
    error.message.resize(header[0]);
    MPI_Bcast(error.message.data(), int(header[0]), MPI_CHAR, first, MPI_COMM_WORLD);
    error.usage = header[1] != 0;
    // Where rank 0 went on, the failing rank is named: on a cluster, the machine to look at.
    if (first != 0) error.message = fmt::format("rank {} of {}: {}", first, size_, error.message);
    return std::unexpected(std::move(error));
#else
    return mine;
#endif
}

void Ranks::quiet_unless_root() {
    if (is_root()) return;
    std::cout.flush();
    std::cerr.flush();
    stderr_ = dup(2);
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    close(null);
}

void Ranks::abort(const std::string& message) const {
    const std::string line = fmt::format("kdop: rank {} of {}: {}\n", rank_, size_, message);
    [[maybe_unused]] const auto written = write(stderr_, line.data(), line.size());
#ifdef KDOP_WITH_MPI
    if (size_ > 1) MPI_Abort(MPI_COMM_WORLD, 1);
#endif
    std::exit(1);
}

} // namespace kdop
