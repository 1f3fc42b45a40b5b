#include "write_files.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
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

Result<void> write_atomically(const std::vector<OutputWriter>& files) {
    std::vector<fs::path> temporaries, placed, created;
    auto abandon = [&](Error error) -> Result<void> {
        std::error_code ignored;
        for (const fs::path& p : temporaries) fs::remove(p, ignored);
        for (const fs::path& p : placed) fs::remove(p, ignored);
        // The folders made for the set go too (innermost first; one that holds anything else stays).
        for (auto it = created.rbegin(); it != created.rend(); ++it) fs::remove(*it, ignored);
        return std::unexpected(std::move(error));
    };
    for (const OutputWriter& f : files) {
        std::error_code ec;
        if (f.path.has_parent_path()) ec = create_directories(f.path.parent_path(), created);
        if (ec)
            return abandon(
                {fmt::format("{}: cannot create directory: {}", f.path.parent_path().string(), ec.message())});
        temporaries.push_back(temporary_path_for(f.path));
        if (auto ok = f.write(temporaries.back()); !ok) return abandon(ok.error());
    }
    for (std::size_t i = 0; i < files.size(); ++i) {
        std::error_code ec;
        // An unchanged file keeps its time stamp, so a build that regenerates it recompiles nothing.
        if (same_content(temporaries[i], files[i].path)) {
            fs::remove(temporaries[i], ec);
            continue;
        }
        fs::rename(temporaries[i], files[i].path, ec);
        if (ec) return abandon({fmt::format("{}: cannot move into place: {}", files[i].path.string(), ec.message())});
        placed.push_back(files[i].path);
    }
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
