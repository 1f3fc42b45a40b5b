#include "generator/variant_files.h"

#include <bit>
#include <cstring>

namespace kdop {
namespace fs = std::filesystem;

std::vector<OutputFile> function_files(const BuiltVariant& v, const fs::path& dir) {
    return {{dir / (v.name + ".glsl"), v.function_glsl},
            {dir / (v.name + ".hlsl"), v.function_hlsl},
            {dir / (v.name + ".wgsl"), v.function_wgsl}};
}

std::vector<OutputFile> glsl_files(const BuiltVariant& v, const fs::path& dir) {
    std::vector<OutputFile> files = function_files(v, dir);
    files.push_back({dir / (v.name + ".comp"), v.compute_glsl});
    return files;
}

std::string spirv_bytes(std::span<const std::uint32_t> words) {
    static_assert(std::endian::native == std::endian::little, "SPIR-V files are written little-endian");
    std::string bytes(words.size() * sizeof(std::uint32_t), '\0');
    std::memcpy(bytes.data(), words.data(), bytes.size());
    return bytes;
}

OutputFile spirv_file(const BuiltVariant& v, const fs::path& dir) {
    return {dir / (v.name + ".spv"), spirv_bytes(v.spirv)};
}

} // namespace kdop
