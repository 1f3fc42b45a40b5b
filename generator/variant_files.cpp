#include "generator/variant_files.h"

#include "generator/reflection_json.h"

#include <bit>
#include <cstring>

namespace kdop {
namespace fs = std::filesystem;

std::vector<OutputFile> function_files(const BuiltVariant& v, const fs::path& dir) {
    std::vector<OutputFile> files;
    for (std::size_t i = 0; i < v.functions.size(); ++i)
        files.push_back({dir / (v.name + std::string(kShaderLanguages[i].extension)), v.functions[i]});
    return files;
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

Result<GeneratedVariants> generate_variants(std::span<const VariantSpec> specs, const fs::path& dir, unsigned threads,
                                            const BuildProgress& progress,
                                            const std::optional<ResolveSettings>& resolve) {
    auto built = build_variants(specs, threads, progress);
    if (!built) return std::unexpected(built.error());
    std::vector<OutputFile> files;
    for (const BuiltVariant& v : *built) {
        for (OutputFile& f : glsl_files(v, dir)) files.push_back(std::move(f));
        files.push_back(spirv_file(v, dir));
    }
    // Their reflection, each entry naming its .spv beside it.
    files.push_back({dir / "variants.json",
                     reflection_json(
                         *built, [](const BuiltVariant& v) { return std::optional(v.name + ".spv"); }, resolve)});
    if (auto ok = write_files_atomically(files); !ok) return std::unexpected(ok.error());
    return GeneratedVariants{std::move(*built), files.size()};
}

} // namespace kdop
