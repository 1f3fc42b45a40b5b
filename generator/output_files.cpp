#include "output_files.h"

#include <fmt/format.h>

#include <bit>
#include <cstring>
#include <fstream>
#include <system_error>

namespace kdop {
namespace fs = std::filesystem;

Result<void> write_files_atomically(const std::vector<OutputFile>& files) {
    std::vector<fs::path> written;
    auto abandon = [&](std::string message) {
        std::error_code ignored;
        for (const fs::path& p : written) fs::remove(p, ignored);
        return fail(std::move(message));
    };
    for (const OutputFile& f : files) {
        std::error_code ec;
        if (f.path.has_parent_path()) fs::create_directories(f.path.parent_path(), ec);
        if (ec) return abandon(fmt::format("{}: cannot create directory: {}", f.path.parent_path().string(), ec.message()));
        fs::path temporary = f.path;
        temporary += ".kdop-partial";
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) return abandon(fmt::format("{}: cannot write: {}", temporary.string(), std::strerror(errno)));
        written.push_back(temporary);
        out.write(f.content.data(), static_cast<std::streamsize>(f.content.size()));
        out.close();
        if (!out) return abandon(fmt::format("{}: write failed", temporary.string()));
    }
    for (std::size_t i = 0; i < files.size(); ++i) {
        std::error_code ec;
        fs::rename(written[i], files[i].path, ec);
        if (ec) return abandon(fmt::format("{}: cannot move into place: {}", files[i].path.string(), ec.message()));
    }
    return {};
}

std::vector<OutputFile> glsl_files(const BuiltVariant& v, const fs::path& dir) {
    return {{dir / (v.name + ".glsl"), v.function_glsl}, {dir / (v.name + ".comp"), v.compute_glsl}};
}

OutputFile spirv_file(const BuiltVariant& v, const fs::path& dir) {
    static_assert(std::endian::native == std::endian::little, "SPIR-V files are written little-endian");
    std::string bytes(v.spirv.size() * sizeof(std::uint32_t), '\0');
    std::memcpy(bytes.data(), v.spirv.data(), bytes.size());
    return {dir / (v.name + ".spv"), std::move(bytes)};
}

} // namespace kdop
