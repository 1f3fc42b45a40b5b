// A private working directory under the system temp directory (for callgrind's and gnuplot's
// files), removed with everything in it when this object dies.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

namespace kdop {

struct ScratchDirectory {
    std::filesystem::path path; // empty if it could not be created

    explicit ScratchDirectory(const std::string& prefix) {
        std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
        if (mkdtemp(pattern.data())) path = pattern;
    }
    ~ScratchDirectory() {
        std::error_code ignored;
        if (!path.empty()) std::filesystem::remove_all(path, ignored);
    }
    ScratchDirectory(const ScratchDirectory&) = delete;
    ScratchDirectory& operator=(const ScratchDirectory&) = delete;
};

} // namespace kdop
