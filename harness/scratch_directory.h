// A private working directory under the system temp directory (for callgrind's and gnuplot's
// files), removed with everything in it when this object dies or the program is interrupted.
#pragma once

#include "core/interrupt.h"

#include <cstdlib>
#include <filesystem>
#include <string>

namespace kdop {

struct ScratchDirectory {
    std::filesystem::path path; // empty if it could not be created

    explicit ScratchDirectory(const std::string& prefix) {
        std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
        auto held = hold_interrupts(); // the folder and its undo step come into being together
        if (!mkdtemp(pattern.data())) return;
        path = pattern;
        undo = OnInterrupt([p = path] {
            std::error_code ignored;
            std::filesystem::remove_all(p, ignored);
        });
    }
    ~ScratchDirectory() {
        undo.forget();
        std::error_code ignored;
        if (!path.empty()) std::filesystem::remove_all(path, ignored);
    }
    OnInterrupt undo;
    ScratchDirectory(const ScratchDirectory&) = delete;
    ScratchDirectory& operator=(const ScratchDirectory&) = delete;
};

} // namespace kdop
