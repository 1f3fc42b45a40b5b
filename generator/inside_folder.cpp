#include "generator/inside_folder.h"

#include <algorithm>

namespace kdop {
namespace fs = std::filesystem;

bool is_inside_folder(const fs::path& file, const fs::path& folder) {
    std::error_code ec;
    const fs::path f = fs::weakly_canonical(file, ec);
    if (ec) return false;
    const fs::path d = fs::weakly_canonical(folder.empty() ? fs::path(".") : folder, ec);
    if (ec) return false;
    auto [end, _] = std::mismatch(d.begin(), d.end(), f.begin(), f.end());
    return end == d.end();
}

} // namespace kdop
