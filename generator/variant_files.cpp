#include "variant_files.h"

#include <fmt/format.h>

#include <bit>
#include <cstring>
#include <fstream>
#include <system_error>

namespace kdop {
namespace fs = std::filesystem;

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
