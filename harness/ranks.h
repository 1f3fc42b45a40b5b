// The processes one command runs as: one, or R ranks started by `mpirun -np R` (Open MPI). kdop
// optimize shares its work over ranks, and kdop choose its fits: each rank reads and evaluates its
// own range of frames, and these collectives hand every rank what the others computed. Nothing here is
// kdop's own protocol: every exchange is an MPI all-gather or broadcast.
//
// MPI is initialized only when the process was started by a launcher (it sets OMPI_COMM_WORLD_SIZE,
// PMI_SIZE or PMIX_RANK), so a plain run neither pays for it nor needs one; a build without MPI
// (none installed) runs as one rank and refuses to be started as several.
#pragma once

#include "core/result.h"

#include <cstddef>
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

    // Whether every rank succeeded: the first failing rank's error (in rank order) on every rank.
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

// Whether a launcher (mpirun) started this process, and how many ranks it says it started (1
// where it does not say, or without a launcher), read before MPI is initialized.
bool started_by_launcher();
int launched_ranks();

} // namespace kdop
