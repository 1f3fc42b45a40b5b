#include "core/write_files.h"

#include "core/input_files.h"
#include "core/interrupt.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <memory>
#include <optional>
#include <system_error>
#include <unistd.h>

namespace kdop {
namespace fs = std::filesystem;

// "<name>.kdop-partial-<pid>-<n><ext>".
fs::path temporary_path_for(const fs::path& path) {
    static std::atomic<unsigned> counter{0};
    fs::path temporary = path;
    temporary.replace_filename(
        fmt::format("{}.kdop-partial-{}-{}{}", path.stem().string(), getpid(), counter++, path.extension().string()));
    return temporary;
}

namespace {

// Creates `dir` and its missing ancestors, adding each one it creates to `created` (outermost first).
std::error_code create_directories(const fs::path& dir, std::vector<fs::path>& created) {
    std::error_code ec;
    std::vector<fs::path> missing;
    for (fs::path p = dir; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        missing.push_back(p);
        if (p == p.parent_path()) break;
    }
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
        // Only folders this call made are this set's to remove: another process may make one first.
        if (fs::create_directory(*it, ec)) created.push_back(*it);
        if (ec) return ec;
    }
    return ec;
}

// Whether both files exist and hold the same bytes.
bool same_content(const fs::path& a, const fs::path& b) {
    std::error_code ec;
    if (!fs::is_regular_file(b, ec) || fs::file_size(a, ec) != fs::file_size(b, ec) || ec) return false;
    std::ifstream in_a(a, std::ios::binary), in_b(b, std::ios::binary);
    std::array<char, 1 << 16> buffer_a, buffer_b;
    while (in_a && in_b) {
        in_a.read(buffer_a.data(), buffer_a.size());
        in_b.read(buffer_b.data(), buffer_b.size());
        if (in_a.gcount() != in_b.gcount() ||
            !std::equal(buffer_a.begin(), buffer_a.begin() + in_a.gcount(), buffer_b.begin()))
            return false;
    }
    return in_a.eof() && in_b.eof();
}

} // namespace

namespace {

// One output set on its way into place, in the state an interruption has to undo. It changes only
// under the interrupt lock, so the undo step (abandon()) sees either a step done or not begun.
struct Transaction {
    std::vector<fs::path> temporaries; // written or being written, not yet moved
    std::vector<fs::path> created;     // folders made for the set, outermost first
    struct Placed {
        fs::path path;
        fs::path previous; // where the file it replaced waits; empty when there was none
    };
    std::vector<Placed> placed;

    // Puts everything back as it was: each replaced file returns to its place (newest first), new
    // files, temporaries and the folders made for them go.
    void abandon() {
        std::error_code ignored;
        for (auto it = placed.rbegin(); it != placed.rend(); ++it) {
            if (it->previous.empty())
                fs::remove(it->path, ignored);
            else
                fs::rename(it->previous, it->path, ignored);
        }
        for (const fs::path& p : temporaries) fs::remove(p, ignored);
        // Innermost first; one that holds anything else stays.
        for (auto it = created.rbegin(); it != created.rend(); ++it) fs::remove(*it, ignored);
        placed.clear();
        temporaries.clear();
        created.clear();
    }
};

// Refuses, before anything is written, a destination that is a folder, a special file or one of
// this run's inputs.
Result<void> check_destinations(const std::vector<OutputWriter>& files) {
    for (const OutputWriter& f : files) {
        std::error_code ec;
        if (fs::is_directory(f.path, ec))
            return fail(fmt::format("{}: is a directory; cannot write a file there", f.path.string()));
        if (auto kind = special_file_kind(f.path))
            return fail(fmt::format("{}: is {}, not a regular file; kdop writes its outputs as new files and "
                                    "would replace it",
                                    f.path.string(), *kind));
        if (auto input = noted_input_at(f.path)) {
            const std::string same =
                input->string() == f.path.string() ? "" : fmt::format(" (the same file as {})", input->string());
            return fail(
                fmt::format("{}: is an input of this run{}; kdop never writes over an input", f.path.string(), same));
        }
    }
    return {};
}

// Moves every temporary into place, keeping each file it replaces (and each stale file) under
// another name until all are in place, so that a failed move can put the previous set back whole.
Result<void> commit(Transaction& t, const std::vector<OutputWriter>& files, const std::vector<fs::path>& stale) {
    for (std::size_t i = 0; i < files.size(); ++i) {
        const fs::path& temporary = t.temporaries[i];
        const fs::path& path = files[i].path;
        std::error_code ec;
        // An unchanged file keeps its time stamp, so a build that regenerates it recompiles nothing.
        if (same_content(temporary, path)) {
            fs::remove(temporary, ec);
            continue;
        }
        Transaction::Placed placed{path, {}};
        const fs::file_status status = fs::symlink_status(path, ec);
        // A folder or a special file made there since the check (by another process) is not this
        // set's to replace.
        if (fs::is_directory(status))
            return fail(fmt::format("{}: cannot move into place: it has become a directory", path.string()));
        if (auto kind = special_file_kind(path))
            return fail(fmt::format("{}: cannot move into place: it has become {}", path.string(), *kind));
        if (fs::exists(status)) {
            // A second name for the previous file keeps it at its path until the new one replaces
            // it; where hard links are not allowed, it is moved aside instead.
            placed.previous = temporary_path_for(path);
            fs::create_hard_link(path, placed.previous, ec);
            if (ec) fs::rename(path, placed.previous, ec);
            if (ec) return fail(fmt::format("{}: cannot keep the previous file: {}", path.string(), ec.message()));
        }
        fs::rename(temporary, path, ec);
        if (ec) {
            std::error_code ignored;
            if (!placed.previous.empty()) fs::rename(placed.previous, path, ignored);
            return fail(fmt::format("{}: cannot move into place: {}", path.string(), ec.message()));
        }
        t.placed.push_back(std::move(placed));
        if (t.placed.size() == 1) test_pause_point("commit"); // a signal amid the moves (tests/signal_test.cpp)
    }
    // A stale file leaves its place under a second name, as a replaced file does, so abandon()
    // puts it back.
    for (const fs::path& path : stale) {
        Transaction::Placed removed{path, temporary_path_for(path)};
        std::error_code ec;
        fs::rename(path, removed.previous, ec);
        if (ec == std::errc::no_such_file_or_directory) continue; // removed by someone else meanwhile
        if (ec) return fail(fmt::format("{}: cannot remove this earlier output: {}", path.string(), ec.message()));
        t.placed.push_back(std::move(removed));
    }
    return {};
}

} // namespace

Result<void> write_atomically(const std::vector<OutputWriter>& files, const std::vector<fs::path>& stale) {
    if (auto ok = check_destinations(files); !ok) return ok;
    auto t = std::make_shared<Transaction>();
    const OnInterrupt undo([t] { t->abandon(); });
    auto abandon = [&](Error error) -> Result<void> {
        auto held = hold_interrupts();
        t->abandon();
        return std::unexpected(std::move(error));
    };
    for (const OutputWriter& f : files) {
        std::error_code ec;
        {
            auto held = hold_interrupts();
            if (f.path.has_parent_path()) ec = create_directories(f.path.parent_path(), t->created);
            if (!ec) t->temporaries.push_back(temporary_path_for(f.path));
        }
        if (ec)
            return abandon(
                {fmt::format("{}: cannot create directory: {}", f.path.parent_path().string(), ec.message())});
        Result<void> written;
        try {
            written = f.write(t->temporaries.back());
        } catch (...) {
            // Out of memory inside an image library: the set is undone, the exception goes on.
            auto held = hold_interrupts();
            t->abandon();
            throw;
        }
        if (!written) return abandon(written.error());
    }
    test_hold_point("write_atomically");
    // The moves happen with the interrupt lock held: an interruption waits for them, then finds the
    // new set complete, which it leaves.
    auto held = hold_interrupts();
    if (interrupted()) return abandon({"interrupted"});
    if (auto ok = commit(*t, files, stale); !ok) {
        t->abandon();
        return ok;
    }
    std::error_code ignored;
    for (const Transaction::Placed& p : t->placed)
        if (!p.previous.empty()) fs::remove(p.previous, ignored);
    *t = {};
    return {};
}

OutputWriter content_writer(const OutputFile& f) {
    return {f.path, [&f](const fs::path& temporary) -> Result<void> {
                std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
                if (!out) return fail(fmt::format("{}: cannot write: {}", f.path.string(), std::strerror(errno)));
                out.write(f.content.data(), static_cast<std::streamsize>(f.content.size()));
                out.close();
                if (!out) return fail(fmt::format("{}: write failed (disk full?)", f.path.string()));
                return {};
            }};
}

Result<void> write_files_atomically(const std::vector<OutputFile>& files) {
    std::vector<OutputWriter> writers;
    for (const OutputFile& f : files) writers.push_back(content_writer(f));
    return write_atomically(writers);
}

std::optional<std::string> special_file_kind(const fs::path& path) {
    std::error_code ec;
    switch (fs::status(path, ec).type()) {
    case fs::file_type::character: return "a character device";
    case fs::file_type::block: return "a block device";
    case fs::file_type::fifo: return "a FIFO";
    case fs::file_type::socket: return "a socket";
    case fs::file_type::unknown: return "a special file";
    default: return std::nullopt; // missing, a dangling link (replaced as a link), a file, a folder
    }
}

Result<void> check_output_file(const fs::path& path, const std::string& option) {
    std::error_code ec;
    if (fs::is_directory(path, ec))
        return fail(fmt::format("{} {}: is a directory; name the file to write", option, path.string()));
    if (auto kind = special_file_kind(path))
        return fail(fmt::format("{} {}: is {}, not a regular file; kdop writes its outputs as new files and would "
                                "replace it: name a file",
                                option, path.string(), *kind));
    return check_output_directory(path.parent_path(), option);
}

Result<void> check_output_directory(const fs::path& dir, const std::string& option) {
    std::error_code ec;
    // An empty path is the current directory: the folder of `--out result.png`.
    fs::path existing = fs::absolute(dir.empty() ? fs::path(".") : dir, ec);
    if (ec) return fail(fmt::format("{}: {}: {}", option, dir.string(), ec.message()));
    while (!fs::exists(existing, ec) && existing.has_parent_path() && existing != existing.parent_path())
        existing = existing.parent_path();
    if (!fs::is_directory(existing, ec))
        return fail(fmt::format("{}: {}: {} is not a directory", option, dir.string(), existing.string()));
    // access() alone is not enough: /proc and read-only mounts can pass it for root. Create and
    // remove a probe file, which is what writing the outputs will need.
    const fs::path probe = existing / fmt::format(".kdop-write-probe-{}", getpid());
    {
        std::ofstream out(probe, std::ios::binary);
        if (!out)
            return fail(fmt::format("{}: {}: cannot create files in {}: {}", option, dir.string(), existing.string(),
                                    std::strerror(errno)));
    }
    fs::remove(probe, ec);
    return {};
}

} // namespace kdop
