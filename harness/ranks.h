// The processes one command runs as: one, or R ranks started by `mpirun -np R` (Open MPI). kdop
// optimize shares its work over ranks, kdop choose its fits and candidates, and kdop taa its sources: each rank reads
// and evaluates its own range of frames, and these collectives hand every rank what the others computed. Nothing here
// is kdop's own protocol: every exchange is an MPI all-gather, broadcast or send, of numbers or of bytes a library
// encoded (kdop taa's figures in CBOR, its images as files).
//
// MPI is initialized only when the process was started by a launcher (it sets OMPI_COMM_WORLD_SIZE,
// PMI_SIZE or PMIX_RANK), so a plain run neither pays for it nor needs one; a build without MPI
// (none installed) runs as one rank and refuses to be started as several.
#pragma once

#include "core/result.h"

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace kdop {

class Ranks {
public:
    // This process's ranks, MPI initialized on the first call where a launcher started it (and
    // finalized at exit). Fails where a launcher started several ranks and kdop was built without MPI.
    static Result<Ranks*> world();

    int rank() const { return rank_; }
    int size() const { return size_; }
    bool is_root() const { return rank_ == 0; }

    // [first, end) of `count` items, rank r's share: contiguous, in rank order, sizes within one.
    std::pair<std::size_t, std::size_t> share(std::size_t count) const;
    // The rank whose share of `count` items holds item `i`.
    int owner(std::size_t i, std::size_t count) const;

    // Fills `all` (the whole array, laid out by item) from every rank's items: rank r has written
    // items [share(items).first, .end), each `per_item[i]` doubles long, and receives the others'.
    void all_gather(std::span<double> all, std::span<const std::size_t> per_item) const;

    // Rank 0's `values` on every rank.
    void broadcast(std::span<double> values) const;

    // balance_over(costs, size()): the same on every rank.
    std::vector<int> balance(std::span<const double> costs) const;

    // Every rank's `mine` on rank 0, in rank order (its own first); empty on the others.
    std::vector<std::string> gather_to_root(const std::string& mine) const;
    // Point to point, for what is too large to gather at once (a run's images, one at a time):
    // `bytes` to rank `to`, which takes them with receive(from), in the order sent.
    void send(const std::string& bytes, int to) const;
    std::string receive(int from) const;

    // Progress under mpirun, for rank 0's one progress line: each other rank tells rank 0 how many
    // steps it has done since it last said, and at the end that it has finished, and whether it
    // succeeded (small messages it does not wait on). Rank 0 takes what has arrived;
    // wait_for_progress() returns once every rank has finished, passing on what arrives meanwhile.
    // Every rank calls its side before the next collective.
    //
    // A failure stops every rank early, not once the others have done their share: rank 0, told of
    // another rank's failure or failing itself (wait_for_progress's `succeeded`), tells every rank
    // still working to stop, and each asks stop_asked() between steps. Each other rank gets one
    // last word from rank 0, "stop" or "done", which the next agree() waits for, so no message is
    // left unread. A rank that stops so has not failed: it gives agree() its success, and the
    // failing rank's error is everyone's.
    void tell_progress(std::size_t steps) const;
    void finish_progress(bool succeeded) const;
    // Rank 0: the steps the other ranks have said they did since the last call.
    std::size_t take_progress() const;
    // Whether this rank should stop its share: on rank 0, whether another rank has said it failed
    // (in what take_progress() took); on the others, whether rank 0 has said stop.
    bool stop_asked() const;
    void wait_for_progress(const std::function<void(std::size_t steps)>& on_steps, bool succeeded) const;

    // Whether every rank succeeded: the first failing rank's error (in rank order) on every rank,
    // "rank R of N: " before it where that is not rank 0.
    Result<void> agree(Result<void> mine) const;

    // Sends the output of every rank but rank 0 to /dev/null: progress, tables and errors come
    // from rank 0 alone (errors reach it through agree()); abort() still speaks.
    void quiet_unless_root();

    // Stops every rank at once: a rank that cannot take part in the next collective (a frame that
    // could no longer be read mid-fit) must not leave the others waiting for it.
    [[noreturn]] void abort(const std::string& message) const;

private:
    int rank_ = 0, size_ = 1;
    int stderr_ = 2; // where abort() writes
};

// The rank of each item of the given costs among `ranks`: each item, largest first (the earlier of
// equals), goes to the rank with the least cost so far (the lowest of equals), which keeps the
// largest share within one item of the mean (Graham's longest-processing-time rule).
std::vector<int> balance_over(std::span<const double> costs, int ranks);

// Whether a launcher (mpirun) started this process, and how many ranks it says it started (1
// where it does not say, or without a launcher), read before MPI is initialized.
bool started_by_launcher();
int launched_ranks();

} // namespace kdop
